// The panel's scalar parameters: one slider per row of scene/params.cpp's table, in the section
// the row names, reading and writing the scene through the row's accessors. A row added to the
// table appears here with no other edit.
#include <imgui.h>

#include "viewer/viewer_ui.h"

namespace cloth::app {
namespace {

bool paramSlider(const ParamSpec& p, double value, Scene& scene) {
    const SliderSpec& s = p.slider;
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
    if (s.scale == SliderScale::Log) flags |= ImGuiSliderFlags_Logarithmic;
    if (p.integer) {
        int x = int(value);
        if (!ImGui::SliderInt(s.label, &x, int(s.min), int(s.max), s.format, flags)) return false;
        p.set(scene, x);
        return true;
    }
    if (!ImGui::SliderScalar(s.label, ImGuiDataType_Double, &value, &s.min, &s.max, s.format,
                             flags))
        return false;
    p.set(scene, value);
    return true;
}

}  // namespace

bool drawParamSliders(Scene& scene, PanelSection section, std::vector<std::string>& drawn) {
    bool changed = false;
    for (const ParamSpec& p : paramTable()) {
        if (p.slider.section != section || !p.get) continue;
        const std::optional<double> value = p.get(scene);
        if (!value) continue;  // not modelled in this scene (the wind's strength without wind)
        drawn.emplace_back(p.path);
        changed |= paramSlider(p, *value, scene);
    }
    return changed;
}

}  // namespace cloth::app
