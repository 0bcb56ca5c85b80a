// clothsim render SCENE --png FILE: simulate headless, draw one frame offscreen, write a PNG
// (DESIGN.md §5). The context is EGL's (src/gpu), so no display is needed.
#include <cstdio>
#include <filesystem>

#include "app/cli.h"
#include "app/solver_factory.h"
#include "core/errors.h"
#include "core/scene_loader.h"
#include "core/stability.h"

#ifdef CLOTH_HAVE_RENDER
#include "gpu/egl_context.h"
#include "render/image.h"
#include "render/renderer.h"
#endif

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim render SCENE --png FILE [options]

Simulates SCENE headless (EGL, no display needed), then draws the final frame offscreen and
writes it as a PNG.

options:
  --png FILE                the image to write (required)
  --steps N                 number of steps (default: duration / integrator.dt; 0 = none)
  --size WxH                image size in pixels (default 960x720)
  --backend cpu|gpu         solver backend (default cpu)
  --precision float|double  CPU arithmetic (default double)
  --set KEY.PATH=JSON       override a scene key, validated like the file (repeatable)
  --colour checker|strain   cloth colours: front/back checker or per-vertex strain
  --wireframe               draw the grid's edges
  --springs                 overlay the springs of a few vertices (structural, shear, bend)
  --help                    this text

exit codes: 0 ok, 1 internal error, 2 invalid input, 3 unstable, 4 no OpenGL context
)";

struct RenderArgs {
    std::string scenePath, png;
    long steps = -1;  // −1: the scene's duration
    int width = 960, height = 720;
    BackendChoice backend;
    std::vector<std::string> sets;
    bool strain = false, wireframe = false, springs = false;
};

void parseSize(const std::string& flag, const std::string& v, RenderArgs& o) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(v.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 ||
        h < 16 || w > 8192 || h > 8192)
        throw InputError("command line", flag, "expected WxH within 16..8192, got '" + v + "'");
    o.width = w;
    o.height = h;
}

long parseSteps(const std::string& flag, const std::string& v) {
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < 0)
        throw InputError("command line", flag, "expected a whole number ≥ 0, got '" + v + "'");
    return n;
}

bool parse(Args& args, RenderArgs& o) {
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") return false;
        if (parseBackendFlag(f, args, o.backend)) continue;
        if (f == "--png")
            o.png = args.value(f);
        else if (f == "--steps")
            o.steps = parseSteps(f, args.value(f));
        else if (f == "--size")
            parseSize(f, args.value(f), o);
        else if (f == "--set")
            o.sets.push_back(args.value(f));
        else if (f == "--colour") {
            const std::string c = args.value(f);
            if (c != "checker" && c != "strain")
                throw InputError("command line", f, "expected checker or strain, got '" + c + "'");
            o.strain = c == "strain";
        } else if (f == "--wireframe")
            o.wireframe = true;
        else if (f == "--springs")
            o.springs = true;
        else
            args.unknown(f);
    }
    if (o.scenePath.empty()) throw InputError("command line", "SCENE", "render needs a scene file");
    if (o.png.empty()) throw InputError("command line", "--png", "render needs --png FILE");
    const std::filesystem::path dir = std::filesystem::path(o.png).parent_path();
    if (!dir.empty() && !std::filesystem::is_directory(dir))
        throw InputError("command line", "--png",
                         "directory '" + dir.string() + "' does not exist");
    return true;
}

// Steps to `total`; false (after saying why) if the run became unstable.
bool simulate(const Scene& scene, Solver& solver, long total) {
    while (solver.stepsDone() < total) {
        const StepResult r = solver.step(std::min(total - solver.stepsDone(), 10000L));
        if (!r.unstable) continue;
        reportUnstable(scene, solver, r, "no image was written");
        return false;
    }
    return true;
}

}  // namespace

int renderCommand(Args& args) {
    RenderArgs o;
    if (!parse(args, o)) {
        std::fputs(kHelp, stdout);
        return kOk;
    }
    const Scene scene = loadScene(o.scenePath, o.sets);
#ifdef CLOTH_HAVE_RENDER
    GlContext::instance();  // EGL, before either solver: the GPU one computes in it
    std::unique_ptr<Solver> solver = makeSolver(scene, o.backend);
    if (!simulate(scene, *solver, o.steps >= 0 ? o.steps : scene.defaultSteps())) return kUnstable;

    render::Renderer renderer;
    renderer.setScene(scene);
    std::vector<std::int64_t> pins;
    for (const Pin& p : scene.pins) pins.push_back(scene.grid().index(p.i, p.j));
    renderer.setPins(pins);
    if (!renderer.updateCloth(*solver))
        throw std::runtime_error("the final state is not finite; no image was written");
    render::RenderOptions options;
    options.colour = o.strain ? render::ColourMode::Strain : render::ColourMode::Checker;
    options.wireframe = o.wireframe;
    options.springs = o.springs;
    const render::OffscreenTarget target(o.width, o.height);
    target.bind();
    const SimState state = solver->read();
    renderer.draw(render::framedCamera(renderer, &state), options, o.width, o.height);
    render::writePng(o.png, target.read());
    std::printf("wrote %s (%dx%d, %ld steps, t = %.4g s, %s)\n", o.png.c_str(), o.width, o.height,
                solver->stepsDone(), solver->time(), solver->name().c_str());
    return kOk;
#else
    (void)scene;
    throw GpuUnavailable("this clothsim was built without the renderer (CLOTH_GPU=OFF)");
#endif
}

}  // namespace cloth::app
