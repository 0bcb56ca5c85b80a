// clothsim: one executable, one subcommand per job (DESIGN.md §5). This is the one place where
// errors become messages and exit codes.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "app/backend_flags.h"
#include "app/bench_flags.h"
#include "app/cli.h"
#include "model/errors.h"

namespace {

constexpr const char* kUsage =
    R"(clothsim — a mass-spring cloth simulator (GPU compute shaders and CPU)

usage:
  clothsim view     [SCENE]                     interactive viewer
  clothsim run      SCENE [options]             headless simulation
  clothsim render   SCENE --png FILE [options]  headless image (EGL)
  clothsim bench    speed|accuracy|stability|realtime [options]
  clothsim validate SCENE                       check a scene, print what it models
  clothsim info                                 GL/EGL device, limits, build
  clothsim shaders  --out DIR SCENE...          every shader source, assembled, for a checker

'clothsim COMMAND --help' describes each command.
exit codes: 0 ok, 1 internal error or a failed write, 2 invalid input, 3 unstable simulation,
            4 no GPU
)";

int dispatch(const std::string& command, cloth::app::Args& args) {
    using namespace cloth;
    using namespace cloth::app;
    if (command == "run") return runCommand(args);
    if (command == "validate") return validateCommand(args);
    if (command == "info") return infoCommand(args);
    if (command == "view") return viewCommand(args);
    if (command == "render") return renderCommand(args);
    if (command == "bench") return benchCommand(args);
    if (command == "shaders") return shadersCommand(args);  // CI's, so not in kUsage
    throw cloth::InputError("command line", command, "unknown command; see clothsim --help");
}

}  // namespace

int main(int argc, char** argv) {
    using namespace cloth;
    using namespace cloth::app;
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        std::fputs(kUsage, argc < 2 ? stderr : stdout);
        return argc < 2 ? kInvalidInput : kOk;
    }
    const std::string command = argv[1];
    Args args(command, std::vector<std::string>(argv + 2, argv + argc));
    try {
        cloth::configureBackends(gpuSetupFromEnvironment());
        return dispatch(command, args);
    } catch (const cloth::InputError& e) {
        std::fprintf(stderr, "clothsim: invalid input: %s\n", e.what());
        return kInvalidInput;
    } catch (const cloth::GpuUnavailable& e) {
        std::fprintf(stderr, "clothsim: GPU backend unavailable: %s\n", e.what());
        return kNoGpu;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "clothsim: out of memory\n");
        return kInternal;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "clothsim: error: %s\n", e.what());
        return kInternal;
    }
}
