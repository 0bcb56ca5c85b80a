// ImGui widgets over doubles that the panel's files share.
#pragma once

#include <imgui.h>

#include <cmath>
#include <glm/glm.hpp>

namespace cloth::app {

// The panel's colours for a warning and for an error.
inline const ImVec4 kWarn{1.0f, 0.8f, 0.2f, 1.0f}, kError{1.0f, 0.35f, 0.3f, 1.0f};

inline bool dragDouble(const char* label, double& v, float speed, double lo, double hi,
                       const char* format = "%.4g", ImGuiSliderFlags flags = 0) {
    return ImGui::DragScalar(label, ImGuiDataType_Double, &v, speed, &lo, &hi, format,
                             flags | ImGuiSliderFlags_AlwaysClamp);
}

inline bool dragVec3(const char* label, glm::dvec3& v, float speed, double lo = -1e3,
                     double hi = 1e3) {
    return ImGui::DragScalarN(label, ImGuiDataType_Double, &v.x, 3, speed, &lo, &hi, "%.3f",
                              ImGuiSliderFlags_AlwaysClamp);
}

inline bool logSlider(const char* label, double& v, double lo, double hi,
                      const char* format = "%.3g") {
    return ImGui::SliderScalar(label, ImGuiDataType_Double, &v, &lo, &hi, format,
                               ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
}

inline glm::dvec3 unitOr(const glm::dvec3& v, const glm::dvec3& fallback) {
    const double n = glm::length(v);
    return n > 1e-9 && std::isfinite(n) ? v / n : fallback;
}

}  // namespace cloth::app
