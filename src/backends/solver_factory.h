// Makes a solver for a backend choice: the one place that knows which backends this build has.
// What a solver tells of its device is in its own interface (Solver::deviceReport).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "cpu/cpu_rows.h"
#include "gpu/gpu_options.h"
#include "solver/solver.h"

namespace cloth {

struct BackendChoice {
    Backend backend = Backend::Cpu;
    Precision precision = Precision::Double;  // CPU only; the GPU computes in float
    int threads = 0;                          // CPU only; 0 = automatic
    GpuOptions gpu{};                         // GPU only: work groups, kernels, read-backs
    CpuIsa isa = CpuIsa::Auto;                // CPU only: the row kernels (cpu/cpu_rows.h)
    bool automatic = false;                   // --backend auto: settleBackend() picks `backend`
};

// Hands the process's GPU settings (the app's environment) to the GPU backend when this build has
// one; before any solver or context is made.
void configureBackends(const GpuSetup& gpu);

// Throws GpuUnavailable when the GPU backend is asked for and cannot run. Settle the choice
// (settleBackend) first: an automatic choice not settled runs on the CPU.
std::unique_ptr<Solver> makeSolver(const Scene& scene, const BackendChoice& choice);

// The backend --backend auto picks (DESIGN.md §5), and why, in words: the GPU when the OpenGL
// context the GPU backend computes in (made headless through EGL, hardware devices first, or the
// window's current one adopted) is on a hardware device, else the CPU. On a software rasteriser
// (llvmpipe, softpipe, swrast) the GPU backend runs about 10–30× slower than the CPU backend
// (docs/performance.md); without a context, a GPU backend in this build, or, for `scene`, a GPU
// that can run it (gpuRefusal), there is no choice; `doubleAsked` (--precision double) needs the
// CPU too, as the GPU computes in float.
struct BackendPick {
    Backend backend = Backend::Cpu;
    std::string reason;  // "as the OpenGL device, llvmpipe (...), is a software rasteriser, ..."
};
BackendPick pickBackend(const Scene* scene, const GpuOptions& options, bool doubleAsked);

// Settles `choice` for `scene` before its solver is made: an automatic choice gets the backend
// pickBackend() names. Returns the one line the user is to be told, or "": which backend auto
// picked and why, or, for --backend gpu on a software rasteriser, a notice that the CPU backend
// is faster there (the GPU backend runs all the same). Makes the GL context (or adopts the
// current one) only when the choice involves the GPU.
std::string settleBackend(BackendChoice& choice, const Scene& scene, bool doubleAsked);

// Why the GPU backend cannot run this scene with these options (a limit of the device, named: the
// grid, a multigrid preconditioner's buffers), or nothing. Throws GpuUnavailable.
std::optional<std::string> gpuRefusal(const Scene& scene, const GpuOptions& options);
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
