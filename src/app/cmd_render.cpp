// clothsim render SCENE --png FILE: simulate headless, draw one frame offscreen, write a PNG
// (DESIGN.md §5). The context is EGL's (src/gpu), so no display is needed.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "app/reports.h"
#include "backends/solver_factory.h"
#include "model/errors.h"
#include "model/stability.h"
#include "scene/scene_loader.h"

#ifdef CLOTH_HAVE_RENDER
#include "render/image.h"
#include "render/renderer.h"
#endif

extern char** environ;

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim render SCENE --png FILE [options]
       clothsim render SCENE --frames DIR --every K [options]

Simulates SCENE headless (EGL, no display needed), then draws the final frame offscreen and
writes it as a PNG; or, with --frames, a PNG every K steps (and the initial one), named
SCENE_<step>.png with the step zero-padded so the names sort, and SCENE.mp4 from them when
ffmpeg is on PATH.

options:
  --png FILE                the image to write
  --frames DIR --every K    a PNG sequence in DIR, one frame every K steps, camera fixed
  --fps F                   the MP4's frame rate (default 30)
  --steps N                 number of steps (default: duration / integrator.dt; 0 = none)
  --size WxH                image size in pixels (default 960x720)
  --backend cpu|gpu|auto    solver backend (default auto: the GPU when its OpenGL device is
                            hardware, else the CPU, about 10-30x faster than the GPU backend on
                            a software rasteriser such as llvmpipe; the pick is said on stderr)
  --precision float|double  CPU arithmetic (default double)
  --set KEY.PATH=JSON       override a scene key, validated like the file (repeatable)
  --colour checker|strain   cloth colours: front/back checker or per-vertex strain
  --strain-scale S          the strain drawn at full colour (default 0.05; woven fabrics
                            stretch about 0.01 under their own weight)
  --wireframe               draw the grid's edges
  --springs                 overlay the springs of a few vertices (structural, shear, bend)
  --help                    this text

exit codes: 0 ok, 1 internal error or a failed write, 2 invalid input (an output path
            that cannot be written included), 3 unstable, 4 no OpenGL context
)";

struct RenderArgs {
    std::string scenePath, png, framesDir;
    long steps = -1;  // −1: the scene's duration
    long every = 0;   // --frames: a frame every `every` steps
    double fps = 30;  // --frames: the MP4's frame rate
    int width = 960, height = 720;
    BackendChoice backend = backendChoiceFromEnvironment();
    bool doubleAsked = false;  // --precision double: --backend auto picks the CPU
    std::vector<std::string> sets;
    bool strain = false, wireframe = false, springs = false;
    float strainScale = 0.05f;  // relative stretch at full colour (render::RenderOptions)
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

float parseStrainScale(const std::string& flag, const std::string& v) {
    char* end = nullptr;
    const double s = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !(s >= 1e-4 && s <= 10))
        throw InputError("command line", flag,
                         "expected a strain within 1e-4..10, got '" + v + "'");
    return float(s);
}

double parseFps(const std::string& flag, const std::string& v) {
    char* end = nullptr;
    const double fps = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !(fps >= 1 && fps <= 240))
        throw InputError("command line", flag, "expected a rate within 1..240, got '" + v + "'");
    return fps;
}

bool parse(Args& args, RenderArgs& o) {
    RunFlags common{o.backend, o.sets};
    o.backend.automatic = true;  // render's default: --backend auto
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") return false;
        if (common.take(f, args)) continue;
        if (f == "--png")
            o.png = args.value(f);
        else if (f == "--steps")
            o.steps = parseSteps(f, args.value(f));
        else if (f == "--size")
            parseSize(f, args.value(f), o);
        else if (f == "--colour") {
            const std::string c = args.value(f);
            if (c != "checker" && c != "strain")
                throw InputError("command line", f, "expected checker or strain, got '" + c + "'");
            o.strain = c == "strain";
        } else if (f == "--strain-scale") {
            o.strainScale = parseStrainScale(f, args.value(f));
        } else if (f == "--frames") {
            o.framesDir = args.value(f);
        } else if (f == "--every") {
            o.every = args.positiveInt(f);
        } else if (f == "--fps") {
            o.fps = parseFps(f, args.value(f));
        } else if (f == "--wireframe")
            o.wireframe = true;
        else if (f == "--springs")
            o.springs = true;
        else
            args.unknown(f);
    }
    if (o.scenePath.empty()) throw InputError("command line", "SCENE", "render needs a scene file");
    common.finish();
    o.doubleAsked = common.doubleAsked();
    if (o.png.empty() && o.framesDir.empty())
        throw InputError("command line", "--png", "render needs --png FILE or --frames DIR");
    if (!o.framesDir.empty() && o.every == 0)
        throw InputError("command line", "--every", "--frames DIR needs --every K");
    if (o.framesDir.empty() && o.every > 0)
        throw InputError("command line", "--frames", "--every K needs --frames DIR");
    return true;
}

#ifdef CLOTH_HAVE_RENDER
// Steps to `total`; false (after saying why) if the run became unstable.
bool simulate(const Scene& scene, Solver& solver, long total) {
    while (solver.stepsDone() < total) {
        const long before = solver.stepsDone();
        StepResult r = solver.step(std::min(total - before, strainCheckSteps(scene.integrator.dt)));
        if (!r.unstable)
            if (auto strained = strainInstability(scene, solver, before)) r = *strained;
        if (!r.unstable) continue;
        reportUnstable(scene, solver, r, "no image was written");
        return false;
    }
    return true;
}

std::string framePng(const RenderArgs& o, const Scene& scene, long step, long total) {
    const int digits = std::max<int>(6, int(std::to_string(total).size()));
    char name[64];
    std::snprintf(name, sizeof name, "_%0*ld.png", digits, step);
    return (std::filesystem::path(o.framesDir) / (scene.name + name)).string();
}

// Whether an executable `name` is on PATH.
bool onPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    if (!path) return false;
    std::string dirs = path;
    for (size_t start = 0; start <= dirs.size();) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::filesystem::path candidate =
            std::filesystem::path(dirs.substr(start, end - start)) / name;
        if (access(candidate.c_str(), X_OK) == 0) return true;
        start = end + 1;
    }
    return false;
}

// Runs argv (argv[0] looked up on PATH) without a shell, so no path needs quoting; its exit
// status, or −1 if it could not be started or did not exit normally.
int runTool(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// SCENE.mp4 from the PNG sequence through ffmpeg, when it is installed; says so when it is not.
void encodeMp4(const RenderArgs& o, const Scene& scene) {
    const std::filesystem::path dir(o.framesDir);
    const std::string mp4 = (dir / (scene.name + ".mp4")).string();
    if (!onPath("ffmpeg")) {
        std::printf("ffmpeg is not on PATH: no MP4 was made; the PNG frames are in %s\n",
                    o.framesDir.c_str());
        return;
    }
    char fps[32];
    std::snprintf(fps, sizeof fps, "%g", o.fps);
    // The glob takes the step-numbered names in order; yuv420p and even sizes play everywhere.
    const std::vector<std::string> argv = {"ffmpeg",
                                           "-loglevel",
                                           "error",
                                           "-y",
                                           "-framerate",
                                           fps,
                                           "-pattern_type",
                                           "glob",
                                           "-i",
                                           (dir / (scene.name + "_*.png")).string(),
                                           "-vf",
                                           "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                           "-c:v",
                                           "libx264",
                                           "-pix_fmt",
                                           "yuv420p",
                                           mp4};
    const int status = runTool(argv);
    if (status == 0)
        std::printf("wrote %s\n", mp4.c_str());
    else
        std::printf("ffmpeg failed (exit %d): no MP4 was made; the PNG frames are in %s\n", status,
                    o.framesDir.c_str());
}

// The renderer and its offscreen target for one command: draws the solver's current state and
// writes it as a PNG.
class Painter {
public:
    Painter(const RenderArgs& o, const Scene& scene) : o_(o), target_(o.width, o.height) {
        renderer_.setScene(scene);
        std::vector<std::int64_t> pins;
        for (const Pin& p : scene.pins) pins.push_back(scene.grid().index(p.i, p.j));
        renderer_.setPins(pins);
        options_.colour = o.strain ? render::ColourMode::Strain : render::ColourMode::Checker;
        options_.strainScale = o.strainScale;
        options_.wireframe = o.wireframe;
        options_.springs = o.springs;
    }
    // Frames the cloth as it is now and the colliders where the solver has them now.
    render::Camera framed(const Solver& solver) {
        renderer_.updateCloth(solver);
        const SimState state = solver.read();
        return render::framedCamera(renderer_, float(o_.width) / float(o_.height), &state);
    }
    void paint(Solver& solver, const std::string& png, const render::Camera& camera) {
        if (!renderer_.updateCloth(solver))
            throw std::runtime_error("the state is not finite; no image was written");
        target_.bind();
        renderer_.draw(camera, options_, o_.width, o_.height);
        render::writePng(png, target_.read());
    }

private:
    const RenderArgs& o_;
    render::Renderer renderer_;
    render::RenderOptions options_;
    render::OffscreenTarget target_;
};

// --frames: a PNG now and every `every` steps up to `total`, all with the first frame's camera
// (a camera reframed per frame would make the video jitter), then the MP4. False (after saying
// why) if the run became unstable.
bool writeFrames(const RenderArgs& o, const Scene& scene, Solver& solver, Painter& painter,
                 long total) {
    const render::Camera camera = painter.framed(solver);
    long frames = 1;
    painter.paint(solver, framePng(o, scene, solver.stepsDone(), total), camera);
    while (solver.stepsDone() < total) {
        const long next = std::min(total, (solver.stepsDone() / o.every + 1) * o.every);
        if (!simulate(scene, solver, next)) return false;
        if (solver.stepsDone() % o.every != 0) break;  // a last partial interval: no frame
        painter.paint(solver, framePng(o, scene, solver.stepsDone(), total), camera);
        ++frames;
    }
    std::printf("wrote %ld frames to %s (%dx%d, %ld steps, %s)\n", frames, o.framesDir.c_str(),
                o.width, o.height, solver.stepsDone(), solver.name().c_str());
    encodeMp4(o, scene);
    return true;
}
#endif

}  // namespace

int renderCommand(Args& args) {
    RenderArgs o;
    if (!parse(args, o)) {
        std::fputs(kHelp, stdout);
        return kOk;
    }
    const Scene scene = loadScene(o.scenePath, o.sets);
#ifdef CLOTH_HAVE_RENDER
    // Before the GL context and the solver: a bad output is refused before anything runs.
    checkOutputFile("--png", o.png);
    checkDistinctFiles({{"SCENE", o.scenePath}, {"--png", o.png}});
    if (!o.framesDir.empty()) prepareFramesDir("--frames", o.framesDir);
    gpuRenderer();  // makes the EGL context before either solver: the GPU one computes in it
    settleBackendAndSay(o.backend, scene, o.doubleAsked, false);
    std::unique_ptr<Solver> solver = makeSolver(scene, o.backend);
    noteUnusedSettings(scene);
    warnUnstableDt(scene);
    const long total = o.steps >= 0 ? o.steps : scene.defaultSteps();
    Painter painter(o, scene);
    if (!o.framesDir.empty() && !writeFrames(o, scene, *solver, painter, total)) return kUnstable;
    if (!simulate(scene, *solver, total)) return kUnstable;
    reportSolveMisses(scene, *solver);  // as run does: implicit Euler's misses are never silent
    if (!o.png.empty()) {
        painter.paint(*solver, o.png, painter.framed(*solver));
        std::printf("wrote %s (%dx%d, %ld steps, t = %.4g s, %s)\n", o.png.c_str(), o.width,
                    o.height, solver->stepsDone(), solver->time(), solver->name().c_str());
    }
    return kOk;
#else
    (void)scene;
    throw GpuUnavailable("this clothsim was built without the renderer (CLOTH_GPU=OFF)");
#endif
}

}  // namespace cloth::app
