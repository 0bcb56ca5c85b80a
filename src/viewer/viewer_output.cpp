// The viewer's files: screenshots (PNG), the current frame (OBJ), the current parameters (a
// scene JSON that `run` loads back to the same parameters). All go to out/ unless given a path.
#include <GL/glew.h>

#include <cstdio>
#include <filesystem>

#include "model/output_file.h"
#include "render/image.h"
#include "scene/scene_json.h"
#include "solver/output.h"
#include "viewer/viewer_session.h"
#include "viewer/viewer_ui.h"

namespace cloth::app {
namespace {

const char* const kOutDir = "out";

// out/STEM.EXT, or out/STEM_2.EXT, ... : never overwrites an earlier file.
std::string freshPath(const std::string& stem, const std::string& ext) {
    std::filesystem::create_directories(kOutDir);
    std::string path = std::string(kOutDir) + "/" + stem + ext;
    for (int n = 2; std::filesystem::exists(path); ++n)
        path = std::string(kOutDir) + "/" + stem + "_" + std::to_string(n) + ext;
    return path;
}

}  // namespace

std::string saveScreenshot(const ViewerUi& ui, const std::string& path) {
    const std::string file = path.empty() ? freshPath("screenshot", ".png") : path;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    render::writePng(file, render::readPixels(ui.viewX + ui.width, ui.height));  // the panel too
    return file;
}

std::string exportObj(const ViewerSession& session) {
    const Scene& s = session.params().scene;
    const std::string file = freshPath(s.name + "_" + std::to_string(session.totalSteps()), ".obj");
    writeObj(file, session.solver().read(), s.name);  // refuses a non-finite state
    return file;
}

std::string saveSceneJson(const ViewerSession& session) {
    const Scene s = session.params().effective();
    const std::string file = freshPath(s.name + "_edited", ".json");
    writeWholeFile(file, sceneToJson(s) + "\n");
    return file;
}

}  // namespace cloth::app
