// Makes a solver for a backend choice: the one place that knows which backends this build has.
// What a solver tells of its device is in its own interface (Solver::deviceReport).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "solver/solver.h"
#include "cpu/cpu_rows.h"
#include "gpu/gpu_options.h"

namespace cloth {

struct BackendChoice {
    Backend backend = Backend::Cpu;
    Precision precision = Precision::Double;  // CPU only; the GPU computes in float
    int threads = 0;                          // CPU only; 0 = automatic
    GpuOptions gpu{};                         // GPU only: work groups, kernels, read-backs
    CpuIsa isa = CpuIsa::Auto;                // CPU only: the row kernels (cpu/cpu_rows.h)
};

// Hands the process's GPU settings (the app's environment) to the GPU backend when this build has
// one; before any solver or context is made.
void configureBackends(const GpuSetup& gpu);

// Throws GpuUnavailable when the GPU backend is asked for and cannot run.
std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice);

// Why the GPU cannot hold this scene's grid with these options (a limit of the device, named),
// or nothing. Throws GpuUnavailable.
std::optional<std::string> gpuSizeRefusal(const Scene& scene, const GpuOptions& options);
// Seconds of one forces pass and one integrate pass (Solver::timePasses), and of one copy kernel
// over as many vec4 as the grid has vertices, each alone, best of `repeats`: what a step's time
// is made of. Throws GpuUnavailable for the copy kernel.
struct GpuPassTimes {
    double forces = 0, integrate = 0, copy = 0;
};
GpuPassTimes gpuPassTimes(Solver& solver, int repeats);
// The GPU copy kernel's read+write bandwidth over `bytes` [bytes/s] (gpu/gpu_bandwidth.h).
// Throws GpuUnavailable.
double gpuCopyBandwidth(std::size_t bytes, int repeats);
// GL_RENDERER of the process's GL context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)": made
// headless through EGL on first use, or the one current on this thread (a window's) adopted,
// with GL's functions loaded. Throws GpuUnavailable.
std::string gpuRenderer();

// The precision a backend's numbers carry (for the CSV's digits).
Precision effectivePrecision(const BackendChoice& choice);

// "HAS_SHEAR HAS_BEND NUM_PLANES=1 ..." for the GPU backend, or why there is none.
std::string gpuVariant(const Scene& scene, const GpuOptions& options = {});

// The GPU device, its limits and the EGL platform, or why there is none.
std::string gpuDescription();

}  // namespace cloth
