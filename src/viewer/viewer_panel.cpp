// The control panel. Every parameter edit goes through one call, session.applyParameters(),
// the same path `view --set` and the tests take.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "model/stability.h"
#include "model/vbd_local.h"
#include "solver/instability.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"
#include "viewer/viewer_widgets.h"

namespace cloth::app {
namespace {

void sceneSection(ViewerSession& session, ViewerUi& ui) {
    const std::string current = session.params().scene.name + ".json";
    if (ImGui::BeginCombo("scene", current.c_str())) {
        for (const std::string& f : ui.sceneFiles)
            if (ImGui::Selectable(f.c_str(), f == current)) ui.loadRequest = f;
        ImGui::EndCombo();
    }
}

void runControls(ViewerSession& session, ViewerUi& ui) {
    if (ImGui::Button(session.paused() ? "Run (space)" : "Pause (space)"))
        session.setPaused(!session.paused());
    ImGui::SameLine();
    if (ImGui::Button("Step (N)")) ui.stepOnce = true;
    ImGui::SameLine();
    if (ImGui::Button("Reset (R)")) session.reset();
    ImGui::SameLine();
    ImGui::Checkbox("v-sync", &ui.vsync);

    BackendChoice b = session.backend();
    int backend = b.backend == Backend::Gpu ? 1 : 0, precision = b.precision == Precision::Float;
    bool changed = ImGui::RadioButton("CPU", &backend, 0);
    ImGui::SameLine();
    changed |= ImGui::RadioButton("GPU", &backend, 1);
    if (backend == 0) {
        ImGui::SameLine(0, 24);
        changed |= ImGui::RadioButton("double", &precision, 0);
        ImGui::SameLine();
        changed |= ImGui::RadioButton("float", &precision, 1);
    }
    if (changed) ui.backendPick.clear();
    if (!ui.backendPick.empty()) ImGui::TextWrapped("%s", ui.backendPick.c_str());
    if (!changed) return;
    b.backend = backend == 1 ? Backend::Gpu : Backend::Cpu;
    b.precision = precision == 1 ? Precision::Float : Precision::Double;
    try {
        session.setBackend(b);
        ui.message.clear();
    } catch (const std::exception& e) {
        ui.message = e.what();
    }
}

// The integrator (docs/integrators.md), Δt and substeps, with the stability bound of
// DESIGN.md §2 and a warning before it is crossed.
bool timeSection(ViewerParams& p, std::vector<std::string>& drawn) {
    IntegratorSpec& in = p.scene.integrator;
    bool changed = false;
    if (ImGui::BeginCombo("integrator", methodName(in.method))) {
        for (Method m : kMethods)
            if (ImGui::Selectable(methodName(m), m == in.method) && m != in.method) {
                in.method = m;
                changed = true;
            }
        ImGui::EndCombo();
    }
    if (in.method == Method::ImplicitEuler &&
        ImGui::BeginCombo("preconditioner", preconditionerName(in.preconditioner))) {
        for (Preconditioner c : kPreconditioners)
            if (ImGui::Selectable(preconditionerName(c), c == in.preconditioner) &&
                c != in.preconditioner) {
                in.preconditioner = c;
                changed = true;
            }
        ImGui::EndCombo();
    }
    changed |= drawParamSliders(p.scene, PanelSection::TimeStep, drawn);
    const double bound = stableDt(p.effective());
    if (in.method == Method::Vbd) {
        // The measured rule for a sheet dropped onto a collider (solver/instability.h).
        const Scene scene = p.effective();
        const double rate = vbdSweepsPerSecond(scene), held = vbdHoldingSweepsPerSecond(scene);
        ImGui::PushStyleColor(ImGuiCol_Text,
                              rate < held ? kWarn : ImGui::GetStyleColorVec4(ImGuiCol_Text));
        ImGui::TextWrapped(
            "no dt bound; %.0f sweeps a simulated second, where a dropped sheet "
            "this size held with %.0f",
            rate, held);
        ImGui::PopStyleColor();
        const Grid g = scene.grid();
        const VbdLevelsRun run = vbdLevelsRun(scene.integrator.translationLevels,
                                              scene.integrator.translationBlockWidth, g.nu, g.nv);
        if (run.levels > 0)
            ImGui::TextWrapped("%d translation levels run, the finest blocks %d x %d", run.levels,
                               run.width, run.height);
    } else if (std::isinf(bound)) {
        ImGui::TextWrapped("stable at any dt (linearised); CG tolerance %.0e", in.tolerance);
    } else if (bound <= 0) {
        ImGui::TextColored(kWarn, "no stable dt: explicit Euler needs damping > 0");
    } else if (in.dt >= bound) {
        ImGui::TextColored(kError, "dt %.3g s is past the stability bound %.3g s", in.dt, bound);
    } else if (in.dt >= 0.8 * bound) {
        ImGui::TextColored(kWarn, "dt is %.0f%% of the stability bound %.3g s", 100 * in.dt / bound,
                           bound);
    } else {
        ImGui::Text("stability bound: dt < %.3g s", bound);
    }
    // A frame's worth of steps the method wants: one for the large-step methods, those inside the
    // bound for the others (after a switch of integrator the scene's dt is the old method's).
    if (const std::optional<FrameStep> fit = frameStep(in, bound)) {
        char label[96];
        std::snprintf(label, sizeof label, "%s: %d x %.3g s",
                      fit->substeps == 1 ? "one step a frame" : "steps inside the bound",
                      fit->substeps, fit->dt);
        if (ImGui::Button(label)) {
            in.dt = fit->dt;
            in.substeps = fit->substeps;
            changed = true;
        }
    }
    return changed;
}

// The table's force sliders, then gravity and the wind's switch and direction (not scalars),
// then the table's wind sliders.
bool forcesSection(ViewerParams& p, std::vector<std::string>& drawn) {
    Scene& s = p.scene;
    bool changed = drawParamSliders(s, PanelSection::Forces, drawn);
    changed |= dragVec3("gravity [m/s2]", s.gravity, 0.05f);
    bool wind = s.wind.has_value();
    if (ImGui::Checkbox("wind", &wind)) {
        s.wind = wind ? std::optional<Wind>(Wind{{1, 0, 0}, 0.1}) : std::nullopt;
        changed = true;
    }
    if (s.wind) {
        glm::dvec3 d = s.wind->direction;
        if (dragVec3("direction", d, 0.02f, -1, 1)) {
            s.wind->direction = unitOr(d, s.wind->direction);
            changed = true;
        }
    }
    changed |= drawParamSliders(s, PanelSection::Wind, drawn);
    // Self-collision: on with half a cell's thickness (the loader's bound is one cell), off; its
    // thickness and friction sliders are the table's, above, while it is on.
    bool self = s.selfCollision.has_value();
    if (s.cloth.nu >= 2 && s.cloth.nv >= 2 && ImGui::Checkbox("self-collision", &self)) {
        const double cell =
            std::min(s.cloth.size.x / (s.cloth.nu - 1), s.cloth.size.y / (s.cloth.nv - 1));
        s.selfCollision =
            self ? std::optional<SelfCollision>(SelfCollision{std::min(0.004, 0.5 * cell), 0.3})
                 : std::nullopt;
        changed = true;
    }
    return changed;
}

bool clothSection(ViewerParams& p, ViewerSession& session, ViewerUi& ui) {
    ClothSpec& c = p.scene.cloth;
    if (ui.resolution[0] == 0) {
        ui.resolution[0] = c.nu;
        ui.resolution[1] = c.nv;
    }
    ImGui::InputInt2("resolution", ui.resolution);
    ui.resolution[0] = std::clamp(ui.resolution[0], 1, 1024);
    ui.resolution[1] = std::clamp(ui.resolution[1], 1, 1024);
    bool changed = false;
    if (ImGui::Button("Rebuild cloth") && ui.resolution[0] * ui.resolution[1] >= 2) {
        c.nu = ui.resolution[0];
        c.nv = ui.resolution[1];
        changed = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("Clear pins")) session.clearPins();
    ImGui::Text("%zu pinned; Ctrl+click a vertex to pin/unpin", session.params().scene.pins.size());
    ImGui::TextDisabled("drag a vertex to pull it");
    return changed;
}

}  // namespace

void drawPanel(ViewerSession& session, ViewerUi& ui) {
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, float(ImGui::GetIO().DisplaySize.y)),
                             ImGuiCond_Always);
    ImGui::Begin("clothsim", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    ImGui::PushItemWidth(170);
    sceneSection(session, ui);
    runControls(session, ui);
    ViewerParams p = session.params();
    bool changed = false;
    ui.drawnParams.clear();
    if (ImGui::CollapsingHeader("Time step", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= timeSection(p, ui.drawnParams);
    if (ImGui::CollapsingHeader("Forces", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= forcesSection(p, ui.drawnParams);
    if (ImGui::CollapsingHeader("Colliders", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= drawCollidersSection(p, session);
    if (ImGui::CollapsingHeader("Cloth and pins")) changed |= clothSection(p, session, ui);
    if (changed) {
        p.scene.pins = session.params().scene.pins;  // pins change through togglePin only
        try {
            session.applyParameters(p);
        } catch (const std::exception& e) {
            ui.message = e.what();
        }
    }
    drawDisplaySection(ui);
    drawDiagnosticsSection(session, ui);
    drawOutputSection(session, ui);
    ImGui::PopItemWidth();
    ImGui::End();
}

void drawInstabilityNotice(ViewerSession& session) {
    if (!session.unstable()) return;
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(size.x * 0.5f + kPanelWidth * 0.5f, size.y * 0.4f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowSize(ImVec2(460, 0));
    ImGui::Begin("The simulation became unstable", nullptr,
                 ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove);
    ImGui::TextColored(kError, "Stopped by an instability check:");
    ImGui::TextWrapped("%s", session.instability().c_str());
    if (ImGui::Button("Reset", ImVec2(120, 0))) session.reset();
    ImGui::End();
}

}  // namespace cloth::app
