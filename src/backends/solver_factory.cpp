#include "backends/solver_factory.h"

#include <cstdio>

#include "model/errors.h"
#include "model/stability.h"

#include "cpu/cpu_backend.h"

// CMake defines CLOTH_GPU_BUILT when it builds the GPU backend (CLOTH_GPU=ON).
#ifdef CLOTH_GPU_BUILT
#include "gpu/egl_context.h"
#include "gpu/gpu_backend.h"
#include "gpu/gpu_bandwidth.h"
#include "gpu/gpu_solver.h"
#include "gpu/gpu_variant.h"
#endif

namespace cloth {

std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice) {
    if (choice.backend == Backend::Cpu)
        return makeCpuSolver(scene, CpuOptions{choice.precision, choice.threads, choice.isa});
#ifdef CLOTH_GPU_BUILT
    return makeGpuSolver(scene, choice.gpu);
#else
    throw GpuUnavailable("this clothsim was built without the GPU backend");
#endif
}

double deviceSecondsPerStep([[maybe_unused]] const Solver& solver) {
#ifdef CLOTH_GPU_BUILT
    if (const auto* gpu = dynamic_cast<const GpuSolver*>(&solver)) return gpu->lastSecondsPerStep();
#endif
    return 0;
}

std::string deviceTimingSource([[maybe_unused]] const Solver& solver) {
#ifdef CLOTH_GPU_BUILT
    if (const auto* gpu = dynamic_cast<const GpuSolver*>(&solver)) return gpu->timingSource();
#endif
    return "";
}

std::string gpuVariantWord([[maybe_unused]] const Solver& solver) {
#ifdef CLOTH_GPU_BUILT
    if (const auto* gpu = dynamic_cast<const GpuSolver*>(&solver))
        return std::to_string(gpu->workGroup().x) + "x" + std::to_string(gpu->workGroup().y) + "/" +
               forcesKernelName(gpu->forcesKernel());
#endif
    return "";
}

std::string gpuDispatchWord([[maybe_unused]] const Solver& solver) {
#ifdef CLOTH_GPU_BUILT
    if (const auto* gpu = dynamic_cast<const GpuSolver*>(&solver))
        return stepDispatchName(gpu->manySteps() ? StepDispatch::ManySteps : StepDispatch::PerStep);
#endif
    return "";
}

std::optional<std::string> gpuSizeRefusal([[maybe_unused]] const Scene& scene,
                                          [[maybe_unused]] const GpuOptions& options) {
#ifdef CLOTH_GPU_BUILT
    const GpuInfo& info = GlContext::instance().info();
    try {
        checkGridFits(scene, chooseWorkGroup({options.workGroupX, options.workGroupY}, &info, options.workGroupKey),
                      info);
    } catch (const InputError& e) {
        return e.reason();
    }
    return std::nullopt;
#else
    throw GpuUnavailable("this clothsim was built without the GPU backend");
#endif
}

GpuPassTimes gpuPassTimes([[maybe_unused]] Solver& solver, [[maybe_unused]] int repeats) {
    GpuPassTimes t;
#ifdef CLOTH_GPU_BUILT
    if (auto* gpu = dynamic_cast<GpuSolver*>(&solver)) {
        t.forces = gpu->timePass(Kernel::Forces, repeats);
        t.integrate = gpu->timePass(Kernel::Integrate, repeats);
        const std::size_t bytes = std::size_t(solver.read().positions.size()) * 16;
        t.copy = 2.0 * double(bytes) / measureGpuCopyBandwidth(bytes, repeats);
    }
#endif
    return t;
}

std::size_t gpuBufferBytes([[maybe_unused]] const Solver& solver) {
#ifdef CLOTH_GPU_BUILT
    if (const auto* gpu = dynamic_cast<const GpuSolver*>(&solver)) return gpu->bufferBytes();
#endif
    return 0;
}

double gpuCopyBandwidth([[maybe_unused]] std::size_t bytes, [[maybe_unused]] int repeats) {
#ifdef CLOTH_GPU_BUILT
    return measureGpuCopyBandwidth(bytes, repeats);
#else
    throw GpuUnavailable("this clothsim was built without the GPU backend");
#endif
}

std::string gpuRenderer() {
#ifdef CLOTH_GPU_BUILT
    return GlContext::instance().info().renderer;
#else
    throw GpuUnavailable("this clothsim was built without the GPU backend");
#endif
}

Precision effectivePrecision(const BackendChoice& choice) {
    return choice.backend == Backend::Gpu ? Precision::Float : choice.precision;
}

std::string gpuVariant([[maybe_unused]] const Scene& scene,
                       [[maybe_unused]] const GpuOptions& options) {
#ifdef CLOTH_GPU_BUILT
    return describeGpuVariant(scene, options);
#else
    return "none (built without the GPU backend)";
#endif
}

std::string gpuDescription() {
#ifdef CLOTH_GPU_BUILT
    try {
        return describeGpu();
    } catch (const GpuUnavailable& e) {
        return std::string("unavailable: ") + e.what();
    }
#else
    return "unavailable: built without the GPU backend";
#endif
}

}  // namespace cloth

