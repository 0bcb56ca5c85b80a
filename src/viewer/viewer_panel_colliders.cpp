// The panel's colliders: each one's switch, placement (plane, sphere), thickness and friction
// (live, through applyParameters like every edit), its motion, and the viewer's drag on it.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "model/collider_limits.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"
#include "viewer/viewer_widgets.h"

namespace cloth::app {
namespace {

void motionText(const Collider& c) {
    if (!c.motion) {
        ImGui::TextDisabled("still");
        return;
    }
    const ColliderMotion& m = *c.motion;
    switch (m.type) {
        case MotionType::Linear:
            ImGui::Text("moves at (%.3g, %.3g, %.3g) m/s", m.velocity.x, m.velocity.y,
                        m.velocity.z);
            break;
        case MotionType::Rotation:
            ImGui::Text("turns %.3g deg/s about (%.2g, %.2g, %.2g)", m.degreesPerSecond, m.axis.x,
                        m.axis.y, m.axis.z);
            break;
        case MotionType::Oscillation:
            ImGui::Text("swings %.3g m at %.3g Hz along (%.2g, %.2g, %.2g)", m.amplitude,
                        m.frequency, m.axis.x, m.axis.y, m.axis.z);
            break;
        case MotionType::Still:
            ImGui::TextDisabled("still");
            break;
    }
}

// Where the viewer's drag has put it, and how fast it may go (docs/colliders.md §7).
void dragText(const ViewerSession& session, std::size_t c, const Collider& col) {
    const double dt = session.params().scene.integrator.dt;
    // The fastest drag clampDragVelocity lets through, the collider's own motion included.
    const double travel = maxColliderStepTravel(col);
    const double limit =
        std::isfinite(travel)
            ? glm::length(clampDragVelocity(glm::dvec3(2 * travel / dt, 0, 0), col, dt))
            : travel;
    const ColliderDrag* d = session.colliderDrag(c);
    if (d == nullptr) {
        if (std::isfinite(limit)) ImGui::TextDisabled("Shift+drag it (at most %.3g m/s)", limit);
        return;
    }
    const glm::dvec3 o = session.colliderOffset(c);
    const double speed = glm::length(d->velocity);
    ImGui::Text("dragged by (%.3f, %.3f, %.3f) m", o.x, o.y, o.z);
    if (speed > 0) ImGui::Text("  moving at %.3g m/s (limit %.3g m/s)", speed, limit);
}

bool placement(Collider& col) {
    bool changed = false;
    if (Plane* pl = col.as<Plane>()) {
        changed |= dragVec3("point", pl->point, 0.01f);
        glm::dvec3 n = pl->normal;
        if (dragVec3("normal", n, 0.01f, -1, 1)) {
            pl->normal = unitOr(n, pl->normal);
            changed = true;
        }
    } else if (Sphere* sp = col.as<Sphere>()) {
        changed |= dragVec3("centre", sp->center, 0.01f);
        changed |= dragDouble("radius [m]", sp->radius, 0.005f, 1e-3, 100);
    }  // box, capsule, mesh: placed in the scene file, moved by dragging
    return changed;
}

}  // namespace

bool drawCollidersSection(ViewerParams& p, const ViewerSession& session) {
    bool changed = false;
    for (std::size_t c = 0; c < p.scene.colliders.size(); ++c) {
        ImGui::PushID(int(c));
        bool on = p.colliderOn[c];
        if (ImGui::Checkbox("##on", &on)) {
            p.colliderOn[c] = on;
            changed = true;
        }
        ImGui::SameLine();
        Collider& col = p.scene.colliders[c];
        ImGui::Text("%s %zu", colliderTypeName(col.shape), c);
        changed |= placement(col);
        // A mesh's thickness must stay inside its band (docs/colliders.md §5).
        const MeshCollider* mesh = col.as<MeshCollider>();
        const double hMax = mesh ? 0.99 * mesh->band : 0.1;
        changed |= logSlider("thickness [m]", col.thickness, 0, hMax, "%.4f");
        const double fLo = 0, fHi = 2;
        changed |= ImGui::SliderScalar("friction", ImGuiDataType_Double, &col.friction, &fLo, &fHi,
                                       "%.2f", ImGuiSliderFlags_AlwaysClamp);
        motionText(col);
        dragText(session, c, col);
        ImGui::PopID();
    }
    if (p.scene.colliders.empty()) ImGui::TextDisabled("none in this scene");
    return changed;
}

}  // namespace cloth::app
