// The viewer's main loop, in the shape of Dear ImGui's example_glfw_opengl3: init → loop (poll,
// new frame, UI, simulate, render, swap) → shutdown.
#include <GL/glew.h>
// GLEW before GLFW's GL header.
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "gpu/egl_context.h"
#include "model/errors.h"
#include "scene/scene_loader.h"
#include "solver/output.h"
#include "viewer/viewer.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"

namespace cloth::app {
namespace {

void glfwError(int code, const char* description) {
    std::fprintf(stderr, "GLFW error 0x%x: %s\n", code, description);
}

// Multisampling smooths the cloth's silhouette for what a GPU does not notice; a software
// rasteriser pays it in every pixel. llvmpipe on 2 cores drew the viewer's frame in 18 ms with 4
// samples and 9.5 ms without at 24², and the 256² cloth's in 66 and 26 ms beside its step
// (docs/viewer.md "Frame rate on a software rasteriser").
constexpr int kSamples = 4;

GLFWwindow* createWindow(const ViewerOptions& o, int samples) {
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_SAMPLES, samples);
    GLFWwindow* window = glfwCreateWindow(o.width, o.height, "clothsim", nullptr, nullptr);
    if (window == nullptr) {
        glfwTerminate();
        throw GpuUnavailable("cannot create a window with an OpenGL 4.3 core context");
    }
    glfwMakeContextCurrent(window);
    return window;
}

// A window with a 4.3+ core context, current on this thread: with --samples' multisampling, or
// by default kSamples on a GPU and none on a software rasteriser (the window made again without
// it once its renderer is known). Throws GpuUnavailable.
GLFWwindow* openWindow(const ViewerOptions& o) {
    glfwSetErrorCallback(glfwError);
    if (!glfwInit()) throw GpuUnavailable("cannot open a window: no display (is DISPLAY set?)");
    GLFWwindow* window = createWindow(o, o.samples >= 0 ? o.samples : kSamples);
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    if (o.samples < 0 && renderer != nullptr && softwareRenderer(renderer)) {
        const std::string name = renderer;
        glfwDestroyWindow(window);
        window = createWindow(o, 0);
        GLint samples = -1;
        glGetIntegerv(GL_SAMPLES, &samples);
        std::fprintf(stderr,
                     "clothsim: view: the window draws without multisampling (GL_SAMPLES %d) on "
                     "%s, a software rasteriser, where %d samples halve the frame rate "
                     "(--samples %d keeps them)\n",
                     int(samples), name.c_str(), kSamples, kSamples);
    }
    glfwSwapInterval(o.vsync ? 1 : 0);
    return window;
}

std::string sceneDirectoryOf(const std::string& scenePath) {
    const std::filesystem::path dir = std::filesystem::path(scenePath).parent_path();
    return (dir.empty() ? std::filesystem::current_path() : dir).string();
}

std::vector<std::string> listScenes(const std::string& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
        if (e.path().extension() == ".json") files.push_back(e.path().filename().string());
    std::sort(files.begin(), files.end());
    return files;
}

// A session on `file`; `edited` (the file with --set overrides) is then applied through
// applyParameters(), like a panel edit.
std::unique_ptr<ViewerSession> openScene(const Scene& file, const std::optional<Scene>& edited,
                                         const BackendChoice& backend) {
    auto session = std::make_unique<ViewerSession>(file, backend);
    if (edited) {
        ViewerParams p = session->params();
        p.scene = *edited;
        session->applyParameters(p);
    }
    return session;
}

void showScene(ViewerSession& session, render::Renderer& renderer, ViewerUi& ui) {
    renderer.setScene(session.params().effective());
    renderer.setPins(session.pinnedVertices());
    ui.homeCamera = render::framedCamera(renderer, float(ui.width) / float(std::max(ui.height, 1)));
    ui.camera = ui.homeCamera;
    ui.resolution[0] = ui.resolution[1] = 0;  // the panel takes the new scene's
}

// The 3-D view takes the framebuffer right of the panel.
void layoutView(GLFWwindow* window, ViewerUi& ui) {
    int fbWidth = 0, fbHeight = 0, winWidth = 1, winHeight = 1;
    glfwGetFramebufferSize(window, &fbWidth, &fbHeight);
    glfwGetWindowSize(window, &winWidth, &winHeight);
    ui.pixelScale = float(fbWidth) / float(std::max(winWidth, 1));
    ui.viewX = std::min(int(kPanelWidth * ui.pixelScale), fbWidth / 2);
    ui.width = fbWidth - ui.viewX;
    ui.height = fbHeight;
}

// Draws the scene; the cloth only while its state is finite (DESIGN.md §2).
void drawScene(ViewerSession& session, render::Renderer& renderer, ViewerUi& ui) {
    renderer.setScene(session.params().effective());
    renderer.setPins(session.pinnedVertices());
    renderer.setContacts(ui.render.contacts ? session.solver().selfContactVertices()
                                            : std::vector<std::int64_t>{});
    renderer.setColliderDrags(session.effectiveDrags());
    if (session.unstable() || !renderer.updateCloth(session.solver())) renderer.clearCloth();
    ui.render.highlightCollider.reset();
    if (ui.drag == ViewerUi::Drag::Collider)
        ui.render.highlightCollider = session.effectiveIndex(ui.colliderDrag.collider);
    ui.render.grabVertex.reset();
    if (const auto& g = session.grabbed()) {
        ui.render.grabVertex = g->vertex;
        ui.render.grabTarget = glm::vec3(g->target);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    renderer.draw(ui.camera, ui.render, ui.width, ui.height, ui.viewX);
}

void initImGui(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 430");
}

void shutdownImGui() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

// A scene picked in the panel replaces the session (on the same backend); a bad one is said in
// the panel and the old one stays.
void loadRequestedScene(ViewerUi& ui, std::unique_ptr<ViewerSession>& session,
                        render::Renderer& renderer) {
    if (!ui.loadRequest) return;
    const std::string path = (std::filesystem::path(ui.sceneDirectory) / *ui.loadRequest).string();
    ui.loadRequest.reset();
    try {
        session = openScene(loadScene(path), std::nullopt, session->backend());
        showScene(*session, renderer, ui);
    } catch (const std::exception& e) {
        ui.message = e.what();
    }
}

// The screenshot after the last frame (--screenshot; none of an unstable state, as the exit 3
// says), and the panel's when asked.
void takeScreenshots(ViewerUi& ui, const ViewerOptions& o, bool last, bool unstable) {
    if (last && !unstable && !o.screenshot.empty()) saveScreenshot(ui, o.screenshot);
    if (std::exchange(ui.screenshotRequested, false)) {
        try {
            ui.message = "wrote " + saveScreenshot(ui);
        } catch (const std::exception& e) {
            ui.message = e.what();
        }
    }
}

}  // namespace

int runViewer(const ViewerOptions& o) {
    // Init: the scene first (bad input is exit 2 with or without a display), then the window
    // and its context, so that the GPU solver adopts this context and its buffers are the ones
    // the renderer draws from.
    const Scene file = loadScene(o.scenePath);
    const std::optional<Scene> edited =
        o.sets.empty() ? std::nullopt : std::optional<Scene>(loadScene(o.scenePath, o.sets));
    GLFWwindow* window = openWindow(o);
    // The GPU library adopts the window's context and loads GL functions; its renderer is named.
    const std::string device = gpuRenderer();
    ViewerUi ui;
    glfwSetWindowUserPointer(window, &ui);
    glfwSetKeyCallback(window, latchKeys);  // before Dear ImGui's, which chains to it
    initImGui(window);
    BackendChoice backend = o.backend;  // --backend auto picks for this window's device
    const std::string pick = settleBackend(backend, edited.value_or(file), o.doubleAsked);
    if (!pick.empty()) std::fprintf(stderr, "clothsim: %s\n", pick.c_str());

    ui.backendPick = pick;
    ui.vsync = o.vsync;
    ui.device = device;
    ui.sceneDirectory = sceneDirectoryOf(o.scenePath);
    ui.sceneFiles = listScenes(ui.sceneDirectory);
    std::unique_ptr<ViewerSession> session = openScene(file, edited, backend);
    auto renderer = std::make_unique<render::Renderer>();
    layoutView(window, ui);  // the first camera frames the scene for the view's shape
    showScene(*session, *renderer, ui);
    double sampleClock = 0;

    // Loop, until the frame after which the window closes: it is drawn and kept (--screenshot,
    // --out-csv) like the last of --frames N.
    for (int frame = 1;; ++frame) {
        glfwPollEvents();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        layoutView(window, ui);
        ui.frameSeconds = ImGui::GetIO().DeltaTime;
        ui.fps = ImGui::GetIO().Framerate;

        // The frame's steps first, so that the panel, the picture and --out-csv show one state;
        // what the panel and the mouse change now acts from the next frame's steps on.
        session->advance(std::exchange(ui.stepOnce, false));
        if ((sampleClock += ui.frameSeconds) >= ViewerHistory::kSampleSeconds) {
            sampleClock = 0;
            session->sampleDiagnostics();
        }
        drawPanel(*session, ui);
        drawInstabilityNotice(*session);
        handleInput(window, *session, ui);
        loadRequestedScene(ui, session, *renderer);

        if (ui.width > 0 && ui.height > 0) drawScene(*session, *renderer, ui);
        if (std::exchange(ui.frameRequested, false) && !session->unstable()) {
            const SimState state = session->solver().read();
            ui.camera.frame(render::stateBounds(state),
                            float(ui.width) / float(std::max(ui.height, 1)));
        }
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        const bool last = (o.frames > 0 && frame >= o.frames) || glfwWindowShouldClose(window);
        takeScreenshots(ui, o, last, session->unstable());
        glfwSwapInterval(ui.vsync ? 1 : 0);
        glfwSwapBuffers(window);
        if (last) break;
    }
    // A run that ends unstable writes no state and exits 3, as `run` does (DESIGN.md §5).
    const bool unstable = session->unstable();
    if (unstable)
        std::fprintf(stderr, "clothsim: %s: %s%s\n", o.scenePath.c_str(),
                     session->instability().c_str(),
                     o.outCsv.empty() ? "" : "; nothing was written for the unstable state");
    else if (!o.outCsv.empty())
        writeCsv(o.outCsv, session->solver().read(), effectivePrecision(session->backend()));

    // Shutdown: GL objects before the context goes.
    renderer.reset();
    session.reset();
    shutdownImGui();
    glfwDestroyWindow(window);
    glfwTerminate();
    return unstable ? kUnstable : kOk;
}

}  // namespace cloth::app
