// Picks a backend for the app: the one place that knows both the CPU and the GPU solver.
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

// Throws GpuUnavailable when the GPU backend is asked for and cannot run.
std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice);

// Device time per step of the solver's last step(n) call [s] and how it was measured
// (GL timer query or glFinish + clock); 0 and "" for the CPU backend.
double deviceSecondsPerStep(const Solver& solver);
std::string deviceTimingSource(const Solver& solver);
// The GPU solver's work-group shape and forces kernel as a word, e.g. "16x16/global", and the
// dispatch it uses ("per-step" or "many-steps", auto resolved); "" for the CPU backend.
std::string gpuVariantWord(const Solver& solver);
std::string gpuDispatchWord(const Solver& solver);
// Why the GPU cannot hold this scene's grid with these options (a limit of the device, named),
// or nothing. Throws GpuUnavailable.
std::optional<std::string> gpuSizeRefusal(const Scene& scene, const GpuOptions& options);
// Seconds of one forces pass, one integrate pass and one copy kernel over as many vec4 as the
// grid has vertices, each alone, best of `repeats`: what a step's time is made of.
struct GpuPassTimes {
    double forces = 0, integrate = 0, copy = 0;
};
GpuPassTimes gpuPassTimes(Solver& solver, int repeats);
// Bytes of GPU memory the solver's buffers hold; 0 for the CPU backend.
std::size_t gpuBufferBytes(const Solver& solver);
// The GPU copy kernel's read+write bandwidth over `bytes` [bytes/s] (gpu/gpu_bandwidth.h).
// Throws GpuUnavailable.
double gpuCopyBandwidth(std::size_t bytes, int repeats);
// GL_RENDERER of the headless context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)". Throws
// GpuUnavailable.
std::string gpuRenderer();

// The precision a backend's numbers carry (for the CSV's digits).
Precision effectivePrecision(const BackendChoice& choice);

// "HAS_SHEAR HAS_BEND NUM_PLANES=1 ..." for the GPU backend, or why there is none.
std::string gpuVariant(const Scene& scene, const GpuOptions& options = {});

// The GPU device, its limits and the EGL platform, or why there is none.
std::string gpuDescription();

}  // namespace cloth
