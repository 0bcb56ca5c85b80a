// clothsim info: the build, the CPU and the GPU device with its limits (DESIGN.md §5).
#include <cstdio>
#include <thread>

#include "app/backend_flags.h"
#include "app/cli.h"
#include "backends/solver_factory.h"

namespace cloth::app {

int infoCommand(Args& args) {
    while (!args.done()) {
        const std::string f = args.flag();
        if (f == "--help") {
            std::fputs(
                "usage: clothsim info\n\nPrints the build, the CPU threads, the GPU (EGL "
                "platform, every EGL device, hardware or software, vendor, GL renderer and "
                "version, compute limits), and which backend --backend auto picks and why.\n",
                stdout);
            return kOk;
        }
        args.unknown(f);
    }
    std::printf("clothsim %s (%s build, %s)\n", CLOTH_VERSION, CLOTH_BUILD_TYPE, __VERSION__);
    std::printf("cpu          %u hardware threads\n", std::thread::hardware_concurrency());
    // One "gpu" heading, the device's lines indented under it.
    std::string gpu = gpuDescription();
    for (size_t at = gpu.find('\n'); at != std::string::npos && at + 1 < gpu.size();
         at = gpu.find('\n', at + 1))
        gpu.insert(at + 1, "             ");
    std::printf("gpu          %s%s", gpu.c_str(), gpu.empty() || gpu.back() != '\n' ? "\n" : "");
    const BackendPick pick = pickBackend(nullptr, backendChoiceFromEnvironment().gpu, false);
    std::printf("auto         %s, %s\n", backendName(pick.backend), pick.reason.c_str());
    return kOk;
}

}  // namespace cloth::app
