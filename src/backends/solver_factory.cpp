#include "backends/solver_factory.h"

#include <algorithm>
#include <string>

#include "cpu/cpu_backend.h"
#include "model/errors.h"
#include "solver/step_control.h"

// CMake defines CLOTH_GPU_BUILT when it builds the GPU backend (CLOTH_GPU=ON): this is the one
// place that asks.
#ifdef CLOTH_GPU_BUILT
#include "gpu/gpu_backend.h"
#include "gpu/gpu_bandwidth.h"
#endif

namespace cloth {
namespace {

// The GPU backend's entry points (gpu/gpu_backend.h), or none in a build without it.
struct GpuEntry {
    std::unique_ptr<Solver> (*make)(const Scene&, const GpuOptions&);
    std::string (*describe)();
    std::string (*variant)(const Scene&, const GpuOptions&);
    std::optional<std::string> (*refusal)(const Scene&, const GpuOptions&);
    double (*copyBandwidth)(std::size_t, int);
    std::string (*renderer)();
    bool (*software)();
    void (*configure)(const GpuSetup&);
};

const GpuEntry* gpuEntry() {
#ifdef CLOTH_GPU_BUILT
    static constexpr GpuEntry gpu{
        makeGpuSolver,           describeGpu,     describeGpuVariant, gpuSceneRefusal,
        measureGpuCopyBandwidth, gpuRendererName, gpuIsSoftware,      configureGpu};
    return &gpu;
#else
    return nullptr;
#endif
}

constexpr const char* kNoGpuBuilt = "this clothsim was built without the GPU backend";

const GpuEntry& requireGpu() {
    if (gpuEntry() == nullptr) throw GpuUnavailable(kNoGpuBuilt);
    return *gpuEntry();
}

// docs/performance.md: the GPU backend on llvmpipe against the CPU backend on the same cores.
constexpr const char* kSoftwareCost = "about 10-30x slower than the CPU backend";

// A GpuUnavailable's message on one line: the context's tries follow its first line on lines of
// their own, each "platform: reason"; they join it after its colon, "; " between them.
std::string oneLine(const std::string& text) {
    std::string line;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t end = std::min(text.find('\n', begin), text.size());
        const std::size_t first = text.find_first_not_of(' ', begin);
        if (first < end) {
            if (!line.empty()) line += line.back() == ':' ? " " : "; ";
            line += text.substr(first, end - first);
        }
        begin = end + 1;
    }
    return line;
}

}  // namespace

void configureBackends(const GpuSetup& gpu) {
    if (gpuEntry() != nullptr) gpuEntry()->configure(gpu);
}

std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice) {
    std::unique_ptr<Solver> backend =
        choice.backend == Backend::Cpu
            ? makeCpuSolver(scene, CpuOptions{choice.precision, choice.threads, choice.isa})
            : requireGpu().make(scene, choice.gpu);
    if (!Features::of(scene).stepControl) return backend;
    return std::make_unique<StepControl>(std::move(backend), scene);
}

BackendPick pickBackend(const Scene* scene, const GpuOptions& options, bool doubleAsked) {
    if (doubleAsked)
        return {Backend::Cpu, "as --precision double asks (the GPU computes in float)"};
    if (gpuEntry() == nullptr) return {Backend::Cpu, std::string("as ") + kNoGpuBuilt};
    try {
        const std::string device = "as the OpenGL device, " + gpuEntry()->renderer() + ", is a ";
        if (gpuEntry()->software())
            return {Backend::Cpu,
                    device + "software rasteriser, where the GPU backend runs " + kSoftwareCost};
        if (scene != nullptr)
            if (const auto why = gpuEntry()->refusal(*scene, options))
                return {Backend::Cpu, "as the GPU backend cannot run this scene: " + *why};
        return {Backend::Gpu, device + "hardware GPU"};
    } catch (const GpuUnavailable& e) {
        return {Backend::Cpu, "as the GPU backend has no OpenGL 4.3 context: " + oneLine(e.what())};
    }
}

std::string settleBackend(BackendChoice& choice, const Scene& scene, bool doubleAsked) {
    if (choice.automatic) {
        const BackendPick pick = pickBackend(&scene, choice.gpu, doubleAsked);
        choice.backend = pick.backend;
        choice.automatic = false;
        return std::string("backend auto: ") + backendName(pick.backend) + ", " + pick.reason;
    }
    if (choice.backend != Backend::Gpu || gpuEntry() == nullptr) return "";
    try {
        if (gpuEntry()->software())
            return "note: the GPU backend runs on " + gpuEntry()->renderer() +
                   ", a software rasteriser, " + kSoftwareCost +
                   " there (--backend cpu or auto picks the CPU)";
    } catch (const GpuUnavailable&) {  // makeSolver says why
    }
    return "";
}

std::optional<std::string> gpuRefusal(const Scene& scene, const GpuOptions& options) {
    return requireGpu().refusal(scene, options);
}

GpuPassTimes gpuPassTimes(Solver& solver, int repeats) {
    const PassTimes passes = solver.timePasses(repeats);
    GpuPassTimes t{passes.forces, passes.integrate, 0};
    const std::size_t bytes = std::size_t(solver.read().positions.size()) * 16;
    t.copy = 2.0 * double(bytes) / gpuCopyBandwidth(bytes, repeats);
    return t;
}

double gpuCopyBandwidth(std::size_t bytes, int repeats) {
    return requireGpu().copyBandwidth(bytes, repeats);
}

std::string gpuRenderer() {
    return requireGpu().renderer();
}

Precision effectivePrecision(const BackendChoice& choice) {
    return choice.backend == Backend::Gpu ? Precision::Float : choice.precision;
}

std::string gpuVariant(const Scene& scene, const GpuOptions& options) {
    if (gpuEntry() == nullptr) return "none (built without the GPU backend)";
    return gpuEntry()->variant(scene, options);
}

std::string gpuDescription() {
    if (gpuEntry() == nullptr) return std::string("unavailable: ") + kNoGpuBuilt;
    try {
        return gpuEntry()->describe();
    } catch (const GpuUnavailable& e) {
        return std::string("unavailable: ") + e.what();
    }
}

}  // namespace cloth
