// clothsim view [SCENE]: the interactive viewer (docs/viewer.md).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "app/reports.h"
#include "backends/solver_factory.h"
#include "model/errors.h"

#ifdef CLOTH_HAVE_VIEWER
#include "viewer/viewer.h"
#endif

namespace cloth::app {
namespace {

#ifdef CLOTH_HAVE_VIEWER
constexpr const char* kHelp = R"(usage: clothsim view [SCENE] [options]

Opens SCENE (default scenes/drape.json) in a window: the simulation runs live, a panel edits
every parameter, the mouse orbits, pans, zooms, grabs and pins. See docs/viewer.md.

options:
  --backend cpu|gpu|auto    solver backend to start with (default auto: the GPU when the
                            window's OpenGL device is hardware, else the CPU, about 10-30x
                            faster than the GPU backend on a software rasteriser such as
                            llvmpipe; the pick is said on stderr and in the panel; switchable
                            live)
  --precision float|double  CPU arithmetic (default double)
  --set KEY.PATH=JSON       change a parameter after loading, as the panel does (repeatable)
  --size WxH                window size (default 1280x800)
  --no-vsync                draw as fast as possible
  --samples N               multisampling, 0 (none) to 16; default 4 on a GPU, none on a
                            software rasteriser such as llvmpipe, where it halves the frame rate
  --frames N                draw N frames, then exit (with --screenshot: for tests)
  --screenshot FILE         after the last frame (of --frames N, or when the window closes:
                            Ctrl+Q), write the window as PNG
  --out-csv FILE            after the last frame, write the solver's state as run --out-csv
  --help                    this text

exit codes: 0 ok, 1 internal error, 2 invalid input, 3 the session ended unstable (not reset
            since), 4 no window with OpenGL 4.3
)";
#endif

}  // namespace

int viewCommand(Args& args) {
#ifdef CLOTH_HAVE_VIEWER
    ViewerOptions o;
    o.backend = backendChoiceFromEnvironment();
    o.backend.automatic = true;  // view's default: --backend auto
    RunFlags common{o.backend, o.sets};
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help") {
            std::fputs(kHelp, stdout);
            return kOk;
        }
        if (common.take(f, args)) continue;
        if (f == "--no-vsync")
            o.vsync = false;
        else if (f == "--frames")
            o.frames = args.positiveInt32(f);
        else if (f == "--samples") {
            const std::string v = args.value(f);
            char* end = nullptr;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || n < 0 || n > 16)
                throw InputError("command line", f, "expected 0 to 16, got '" + v + "'");
            o.samples = int(n);
        } else if (f == "--screenshot")
            o.screenshot = args.value(f);
        else if (f == "--out-csv")
            o.outCsv = args.value(f);
        else if (f == "--size") {
            const std::string v = args.value(f);
            if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 64 ||
                o.height < 64 || o.width > 16384 || o.height > 16384)
                throw InputError("command line", f,
                                 "expected WxH (64x64 to 16384x16384), got '" + v + "'");
        } else
            args.unknown(f);
    }
    common.finish();  // --backend gpu --precision double is refused, as run and render refuse it
    checkOutputFile("--screenshot", o.screenshot);
    checkOutputFile("--out-csv", o.outCsv);
    checkDistinctFiles(
        {{"SCENE", o.scenePath}, {"--screenshot", o.screenshot}, {"--out-csv", o.outCsv}});
    if (o.frames > 0) o.vsync = false;  // a scripted run need not wait for the display
    o.doubleAsked = common.doubleAsked();
    return runViewer(o);
#else
    (void)args;
    throw GpuUnavailable("this clothsim was built without the viewer (GLFW, Dear ImGui)");
#endif
}

}  // namespace cloth::app
