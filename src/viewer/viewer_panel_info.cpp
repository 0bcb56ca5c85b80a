// The panel's lower sections: what is drawn, how fast it runs (with plots of energy, strain and
// step time), and the files it writes.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "solver/instability.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"
#include "viewer/viewer_widgets.h"

namespace cloth::app {
namespace {

void plot(const char* label, const std::vector<float>& v, const char* unit) {
    if (v.empty()) {
        ImGui::TextDisabled("%s: collecting...", label);
        return;
    }
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%.4g %s", double(v.back()), unit);
    const float pad = 0.05f * std::max(*hi - *lo, 1e-6f);
    ImGui::PlotLines(label, v.data(), int(v.size()), 0, overlay, *lo - pad, *hi + pad,
                     ImVec2(0, 48));
}

}  // namespace

void drawDisplaySection(ViewerUi& ui) {
    if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
    render::RenderOptions& r = ui.render;
    int mode = r.colour == render::ColourMode::Strain ? 1 : 0;
    ImGui::RadioButton("checker", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("strain (C)", &mode, 1);
    r.colour = mode == 1 ? render::ColourMode::Strain : render::ColourMode::Checker;
    if (mode == 1) ImGui::SliderFloat("full colour at", &r.strainScale, 0.001f, 1.0f, "%.3f");
    ImGui::Checkbox("wireframe (W)", &r.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("springs", &r.springs);
    ImGui::Checkbox("pins", &r.pins);
    ImGui::SameLine();
    ImGui::Checkbox("colliders", &r.colliders);
    ImGui::SameLine();
    ImGui::Checkbox("wind", &r.wind);
    ImGui::SameLine();
    ImGui::Checkbox("contacts", &r.contacts);
    if (r.springs)
        ImGui::TextDisabled("springs: structural red, shear green, bend magenta (hover a vertex)");
    if (ImGui::Button("Frame cloth (F)")) ui.frameRequested = true;
    ImGui::SameLine();
    if (ImGui::Button("Reset view (Home)")) ui.camera = ui.homeCamera;
}

void drawDiagnosticsSection(const ViewerSession& session, const ViewerUi& ui) {
    if (!ImGui::CollapsingHeader("Diagnostics", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const Solver& solver = session.solver();
    const double steps = double(session.lastSteps());
    const double stepSeconds = session.lastStepSeconds();
    const double vertices =
        double(session.params().scene.cloth.nu) * session.params().scene.cloth.nv;
    const double simPerFrame = steps * session.params().scene.integrator.dt;
    ImGui::TextWrapped("%s", solver.name().c_str());
    ImGui::TextDisabled("%s", ui.device.c_str());
    ImGui::Text("%.1f FPS   sim %.2f ms/frame", ui.fps, 1e3 * stepSeconds);
    if (steps > 0) {
        ImGui::Text("%.4f ms/step   %.3g vertex-steps/s", 1e3 * stepSeconds / steps,
                    vertices * steps / std::max(stepSeconds, 1e-9));
        ImGui::Text("speed %.3gx real time", simPerFrame / std::max(ui.frameSeconds, 1e-6));
    } else {
        ImGui::TextDisabled(session.paused() ? "paused" : "not stepping");
    }
    ImGui::Text("t = %.4f s, %ld steps", session.simTime(), session.totalSteps());
    if (solver.features().stepControl) {
        const StepControlStats c = solver.stepControlStats();
        ImGui::Text("step control: %ld steps split, shortest dt/%d", c.split, 1 << c.deepest);
    }
    const ViewerHistory& h = session.history();
    plot("energy", h.energy, "J");
    plot("max strain", h.maxStrain, "");
    plot("step time", h.stepMs, "ms");
    if (session.params().scene.integrator.method == Method::ImplicitEuler) {
        plot("CG iterations", h.iterations, "per step");
        plot("CG log10 |r|/|b|", h.residual, "");
        // Never silent (docs/integrators.md): solves that missed the tolerance, each kind apart.
        const SolveStats& s = solver.solveStats();
        ImGui::PushStyleColor(ImGuiCol_Text, kWarn);
        if (s.misses > s.breakdowns)
            ImGui::TextWrapped("%ld of %ld solves stopped at max_iterations",
                               s.misses - s.breakdowns, s.solves);
        if (s.breakdowns > 0)
            ImGui::TextWrapped("%ld of %ld solves broke down (p.Ap <= 0 or not finite): try %s",
                               s.breakdowns, s.solves,
                               breakdownRemedy(session.params().scene, solver).c_str());
        ImGui::PopStyleColor();
    }
}

void drawOutputSection(const ViewerSession& session, ViewerUi& ui) {
    if (!ImGui::CollapsingHeader("Output", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::Button("Screenshot (F12)")) ui.screenshotRequested = true;
    ImGui::SameLine();
    try {
        if (ImGui::Button("Export OBJ")) ui.message = "wrote " + exportObj(session);
        ImGui::SameLine();
        if (ImGui::Button("Save scene")) ui.message = "wrote " + saveSceneJson(session);
    } catch (const std::exception& e) {
        ui.message = e.what();
    }
    if (!ui.message.empty()) ImGui::TextWrapped("%s", ui.message.c_str());
}

}  // namespace cloth::app
