#include "app/solver_factory.h"

#include <cstdio>

#include "core/errors.h"
#include "core/stability.h"

#if defined(CLOTH_HAVE_GPU) && __has_include("gpu/gpu_backend.h")
#include "gpu/egl_context.h"
#include "gpu/gpu_backend.h"
#include "gpu/gpu_bandwidth.h"
#include "gpu/gpu_solver.h"
#include "gpu/gpu_variant.h"
#define CLOTH_GPU_BUILT 1
#endif

namespace cloth::app {

bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice) {
    if (flag == "--backend")
        choice.backend = parseBackend(flag, args.value(flag));
    else if (flag == "--precision")
        choice.precision = parsePrecision(flag, args.value(flag));
    else if (flag == "--threads")
        choice.threads = int(args.positiveInt(flag));
    else
        return false;
    return true;
}

Backend parseBackend(const std::string& flag, const std::string& value) {
    if (value == "cpu") return Backend::Cpu;
    if (value == "gpu") return Backend::Gpu;
    throw InputError("command line", flag, "expected cpu or gpu, got '" + value + "'");
}

Precision parsePrecision(const std::string& flag, const std::string& value) {
    if (value == "float") return Precision::Float;
    if (value == "double") return Precision::Double;
    throw InputError("command line", flag, "expected float or double, got '" + value + "'");
}

std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice) {
    if (choice.backend == Backend::Cpu)
        return makeCpuSolver(scene, CpuOptions{choice.precision, choice.threads});
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
        checkGridFits(scene, chooseWorkGroup({options.workGroupX, options.workGroupY}, &info),
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

void reportUnstable(const Scene& scene, const Solver& solver, const StepResult& r,
                    const std::string& consequence) {
    const double dt = scene.integrator.dt;
    if (r.firstBadStep == r.lastBadStep)
        std::fprintf(stderr, "clothsim: %s: unstable at step %ld (t = %.6g s): %s\n",
                     scene.source.c_str(), r.firstBadStep, r.firstBadStep * dt, r.reason.c_str());
    else
        std::fprintf(stderr,
                     "clothsim: %s: unstable between steps %ld and %ld (t = %.6g..%.6g s): %s\n",
                     scene.source.c_str(), r.firstBadStep, r.lastBadStep, r.firstBadStep * dt,
                     r.lastBadStep * dt, r.reason.c_str());
    std::fprintf(stderr, "clothsim: %s [%s]; %s\n", stabilityAdvice(scene).c_str(),
                 solver.name().c_str(), consequence.c_str());
}

Precision effectivePrecision(const BackendChoice& choice) {
    return choice.backend == Backend::Gpu ? Precision::Float : choice.precision;
}

std::string gpuVariant([[maybe_unused]] const Scene& scene) {
#ifdef CLOTH_GPU_BUILT
    return describeGpuVariant(scene);
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

}  // namespace cloth::app

namespace cloth::app {

void reportSolveMisses(const Scene& scene, const Solver& solver) {
    const SolveStats& s = solver.solveStats();
    if (s.misses == 0) return;
    std::fprintf(stderr,
                 "clothsim: %s: warning: %ld of %ld implicit solves stopped at "
                 "integrator.max_iterations = %d before |r| <= %g |b| (first at step %ld, worst "
                 "relative residual %.3g); raise integrator.max_iterations or lower dt\n",
                 scene.source.c_str(), s.misses, s.solves, scene.integrator.maxIterations,
                 scene.integrator.tolerance, s.firstMissStep, s.worstResidual);
}

}  // namespace cloth::app
