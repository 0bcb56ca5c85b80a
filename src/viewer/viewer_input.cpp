// Mouse and keyboard: left-drag orbits (or, on a vertex, grabs it with a spring to the cursor on
// the plane facing the camera through the grabbed point), Ctrl+click pins or unpins a vertex,
// Shift+left drag on a collider drags it on the plane facing the camera (docs/viewer.md), right/
// middle or Shift+left drag elsewhere pans, the wheel zooms. Input ImGui wants is left to ImGui.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <stdexcept>
#include <utility>

#include "render/collider_pick.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"

namespace cloth::app {
namespace {

render::Ray cursorRay(GLFWwindow* window, const ViewerUi& ui) {
    double x = 0, y = 0;
    int w = 1, h = 1;
    glfwGetCursorPos(window, &x, &y);
    glfwGetWindowSize(window, &w, &h);
    const float left = float(ui.viewX) / ui.pixelScale;  // the 3-D view starts after the panel
    const glm::vec2 ndc(2 * (float(x) - left) / std::max(float(w) - left, 1.0f) - 1,
                        1 - 2 * float(y) / float(std::max(h, 1)));
    return ui.camera.ray(ndc, float(ui.width) / float(std::max(ui.height, 1)));
}

std::optional<std::int64_t> pickVertex(GLFWwindow* window, const ViewerSession& session,
                                       const ViewerUi& ui, glm::vec3& position) {
    if (session.unstable()) return std::nullopt;
    const SimState state = session.solver().read();
    const auto k = render::nearestToRay(cursorRay(window, ui), state.positions);
    if (k) position = glm::vec3(state.positions[std::size_t(*k)]);
    return k;
}

// Shift + left press: the collider under the cursor, if any, starts a drag (planes are not
// picked: render/collider_pick.h). False when nothing was picked.
bool startColliderDrag(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    if (session.unstable()) return false;
    const auto hit =
        render::pickCollider(cursorRay(window, ui), session.params().effective().colliders,
                             session.solver().time(), session.effectiveDrags());
    if (!hit) return false;
    ViewerUi::ColliderDrag& d = ui.colliderDrag;
    d.collider = session.paramsIndex(hit->index);
    d.picked = hit->point;
    d.normal = glm::dvec3(ui.camera.forward());
    d.startOffset = session.colliderOffset(d.collider);
    try {
        session.dragCollider(d.collider, d.startOffset);
        ui.drag = ViewerUi::Drag::Collider;
    } catch (const std::invalid_argument& e) {  // the GPU backend cannot drag yet
        ui.message = e.what();
        ui.drag = ViewerUi::Drag::None;
    }
    return true;
}

void moveCollider(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    const ViewerUi::ColliderDrag& d = ui.colliderDrag;
    const auto target =
        render::dragTarget(cursorRay(window, ui), d.picked, d.normal, d.startOffset);
    if (!target) return;
    try {
        session.dragCollider(d.collider, *target);
    } catch (const std::invalid_argument& e) {
        ui.message = e.what();
        ui.drag = ViewerUi::Drag::None;
    }
}

// The keys latched since the last frame (latchKeys), in the order they came.
void keyboard(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    const std::vector<ViewerUi::KeyPress> keys = std::exchange(ui.keysPressed, {});
    for (const ViewerUi::KeyPress& k : keys) {
        if (k.key == GLFW_KEY_Q && (k.mods & GLFW_MOD_CONTROL) != 0)
            glfwSetWindowShouldClose(window, GLFW_TRUE);
        if (ImGui::GetIO().WantCaptureKeyboard) continue;  // typing into the panel
        switch (k.key) {
            case GLFW_KEY_SPACE:
                session.setPaused(!session.paused());
                break;
            case GLFW_KEY_N:
                ui.stepOnce = true;
                break;
            case GLFW_KEY_R:
                session.reset();
                break;
            case GLFW_KEY_F:
                ui.frameRequested = true;
                break;
            case GLFW_KEY_HOME:
                ui.camera = ui.homeCamera;
                break;
            case GLFW_KEY_W:
                ui.render.wireframe = !ui.render.wireframe;
                break;
            case GLFW_KEY_C:
                ui.render.colour = ui.render.colour == render::ColourMode::Strain
                                       ? render::ColourMode::Checker
                                       : render::ColourMode::Strain;
                break;
            case GLFW_KEY_F12:
            case GLFW_KEY_P:
                ui.screenshotRequested = true;
                break;
            default:
                break;
        }
    }
}

void press(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    const ImGuiIO& io = ImGui::GetIO();
    const bool shiftLeft = ImGui::IsMouseClicked(ImGuiMouseButton_Left) && io.KeyShift;
    if (shiftLeft && startColliderDrag(window, session, ui)) return;
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Right) ||
        ImGui::IsMouseClicked(ImGuiMouseButton_Middle) || shiftLeft) {
        ui.drag = ViewerUi::Drag::Pan;
        return;
    }
    if (!ImGui::IsMouseClicked(ImGuiMouseButton_Left)) return;
    glm::vec3 position;
    const auto k = pickVertex(window, session, ui, position);
    if (k && io.KeyCtrl) {
        session.togglePin(*k);
        ui.drag = ViewerUi::Drag::None;
    } else if (k) {
        ui.grabPlanePoint = position;
        session.grab(*k, glm::dvec3(position));
        ui.drag = ViewerUi::Drag::Grab;
    } else {
        ui.drag = ViewerUi::Drag::Orbit;
    }
}

void drag(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    const ImVec2 d = ImGui::GetIO().MouseDelta;
    switch (ui.drag) {
        case ViewerUi::Drag::Orbit:
            ui.camera.orbit(d.x, d.y);
            break;
        case ViewerUi::Drag::Pan:
            ui.camera.pan(d.x, d.y, float(ui.height));
            break;
        case ViewerUi::Drag::Grab:
            if (const auto& g = session.grabbed()) {
                const auto hit = render::intersectPlane(cursorRay(window, ui), ui.grabPlanePoint,
                                                        ui.camera.forward());
                if (hit) session.grab(g->vertex, glm::dvec3(*hit));
            }
            break;
        case ViewerUi::Drag::Collider:
            moveCollider(window, session, ui);
            break;
        case ViewerUi::Drag::None:
            break;
    }
}

}  // namespace

void latchKeys(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    if (action != GLFW_PRESS) return;
    if (auto* ui = static_cast<ViewerUi*>(glfwGetWindowUserPointer(window)))
        ui->keysPressed.push_back({key, mods});
}

void handleInput(GLFWwindow* window, ViewerSession& session, ViewerUi& ui) {
    keyboard(window, session, ui);
    const ImGuiIO& io = ImGui::GetIO();
    const bool anyDown = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
    if (!anyDown) {
        if (ui.drag == ViewerUi::Drag::Grab) session.release();
        if (ui.drag == ViewerUi::Drag::Collider) session.releaseCollider(ui.colliderDrag.collider);
        ui.drag = ViewerUi::Drag::None;
    }
    if (ui.drag != ViewerUi::Drag::None) {
        drag(window, session, ui);
        return;
    }
    if (io.WantCaptureMouse) return;
    if (io.MouseWheel != 0) ui.camera.zoom(io.MouseWheel);
    press(window, session, ui);
    if (ui.render.springs && !anyDown) {  // the overlay follows the vertex under the cursor
        glm::vec3 unused;
        if (const auto k = pickVertex(window, session, ui, unused)) ui.render.springVertices = {*k};
    }
}

}  // namespace cloth::app
