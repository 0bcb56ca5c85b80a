// What the viewer's panel and input handling share besides the session: camera, display
// options, requests for the main loop, and frame timing.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/renderer.h"
#include "scene/params.h"

struct GLFWwindow;

namespace cloth::app {

class ViewerSession;
struct ViewerParams;

struct ViewerUi {
    render::Camera camera;
    render::Camera homeCamera;  // what "reset view" returns to
    render::RenderOptions render;
    bool vsync = true;
    bool screenshotRequested = false;
    bool frameRequested = false;  // "frame the cloth" on the next frame
    bool stepOnce = false;
    std::string sceneDirectory;
    std::vector<std::string> sceneFiles;  // *.json in sceneDirectory
    std::optional<std::string> loadRequest;
    std::string message;         // the last file written, or an error
    std::string device;          // GL renderer of the window
    std::string backendPick;     // what --backend auto picked and why, until the backend changes
    int resolution[2] = {0, 0};  // the panel's pending grid size; 0: take the scene's
    int width = 1, height = 1;   // the 3-D view right of the panel, framebuffer [px]
    int viewX = 0;               // its left edge, framebuffer [px]
    float pixelScale = 1;        // framebuffer pixels per window unit (HiDPI)
    // The key paths of the parameter sliders the panel drew in its last frame: all of them come
    // from scene/params.cpp's table (tests check this against the table).
    std::vector<std::string> drawnParams;

    // Keys pressed since the last frame with their modifiers (GLFW_MOD_*), latched by a GLFW
    // callback (latchKeys): Dear ImGui 1.86 reads the keys' state once a frame, so a key pressed
    // and released between two frames (a quick tap at a low frame rate) would be lost.
    struct KeyPress {
        int key, mods;
    };
    std::vector<KeyPress> keysPressed;

    // Timing of the last frame.
    double frameSeconds = 0;  // wall time between frames
    double fps = 0;

    // Mouse interaction in progress.
    enum class Drag { None, Orbit, Pan, Grab, Collider } drag = Drag::None;
    glm::vec3 grabPlanePoint{0};
    // A collider drag (Shift + left drag on a collider): which one (params order), the picked
    // point and the view direction then (the drag plane), and its displacement then.
    struct ColliderDrag {
        std::size_t collider = 0;
        glm::dvec3 picked{0}, normal{0, 0, 1}, startOffset{0};
    } colliderDrag;
};

// The panel (viewer_panel.cpp): edits a copy of the parameters and hands it to
// session.applyParameters() when anything changed.
void drawPanel(ViewerSession& session, ViewerUi& ui);
inline constexpr float kPanelWidth = 360;  // [window units]
// Its colliders (viewer_panel_colliders.cpp): the switches, placement, thickness, friction,
// motion and drag state of each; edits `p`, returns whether anything changed.
bool drawCollidersSection(ViewerParams& p, const ViewerSession& session);
// Its scalar parameters (viewer_panel_params.cpp): a slider for each row of scene/params.cpp's
// table in `section` that the scene models; appends the rows' key paths to `drawn`.
bool drawParamSliders(Scene& scene, PanelSection section, std::vector<std::string>& drawn);
// Its lower sections (viewer_panel_info.cpp): display modes, diagnostics and plots, output.
void drawDisplaySection(ViewerUi& ui);
void drawDiagnosticsSection(const ViewerSession& session, const ViewerUi& ui);
void drawOutputSection(const ViewerSession& session, ViewerUi& ui);
// A centred notice with a reset button while the run is unstable.
void drawInstabilityNotice(ViewerSession& session);

// Mouse and keyboard (viewer_input.cpp): camera, picking, grab, pins, shortcuts.
void handleInput(GLFWwindow* window, ViewerSession& session, ViewerUi& ui);
// The GLFW key callback that fills ViewerUi::keysPressed (the window's user pointer is the
// ViewerUi); installed before Dear ImGui's, which calls it on.
void latchKeys(GLFWwindow* window, int key, int scancode, int action, int mods);

// Files (viewer_output.cpp); each returns the path written and throws std::runtime_error.
std::string saveScreenshot(const ViewerUi& ui, const std::string& path = "");
std::string exportObj(const ViewerSession& session);
std::string saveSceneJson(const ViewerSession& session);

}  // namespace cloth::app
