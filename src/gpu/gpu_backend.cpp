#include "gpu/gpu_backend.h"

#include "gpu/egl_context.h"
#include "gpu/gpu_solver.h"
#include "gpu/gpu_variant.h"
#include "model/errors.h"
#include "model/float_range.h"

namespace cloth {

std::unique_ptr<Solver> makeGpuSolver(const Scene& scene, const GpuOptions& options) {
    checkFloatRange(scene);  // the GPU computes in float
    return std::make_unique<GpuSolver>(scene, options);
}

std::string describeGpu() {
    return GlContext::instance().info().describe();
}

std::string describeGpuVariant(const Scene& scene, const GpuOptions& options) {
    std::string line;
    for (const auto& [name, value] :
         gpuDefines(scene, chooseWorkGroup({options.workGroupX, options.workGroupY}, nullptr,
                                           options.workGroupKey))) {
        if (name == "SPRING_OFFSETS") continue;  // the table rows; NUM_SPRING_OFFSETS says enough
        const bool quote = value.find(' ') != std::string::npos;
        line += (line.empty() ? "" : " ") + name;
        if (!value.empty()) line += "=" + (quote ? "\"" + value + "\"" : value);
    }
    return line;
}

std::optional<std::string> gpuSceneRefusal(const Scene& scene, const GpuOptions& options) {
    const GpuInfo& info = GlContext::instance().info();
    try {
        checkSceneFits(
            scene,
            chooseWorkGroup({options.workGroupX, options.workGroupY}, &info, options.workGroupKey),
            info);
    } catch (const InputError& e) {
        return e.reason();
    }
    return std::nullopt;
}

std::string gpuRendererName() {
    return GlContext::instance().info().renderer;
}

bool gpuIsSoftware() {
    return GlContext::instance().info().software;
}

}  // namespace cloth
