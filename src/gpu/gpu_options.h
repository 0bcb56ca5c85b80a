// How the GPU backend runs a scene: work groups, kernels and dispatch, none of which changes the
// physics; and where the process finds its shaders and device. No GL here: the app's option
// parsing and the tests include it freely.
#pragma once

#include <string>

#include "model/multigrid_levels.h"

namespace cloth {

// Where pass 1 reads the neighbours' positions: straight from the SSBO, or from a work group's
// tile and 2-vertex halo loaded into shared memory once (docs/performance.md measures both).
enum class ForcesKernel { Global, Tiled };

// Dispatches per step: one per pass (PerStep), or many steps in one dispatch of one work group
// holding the whole grid (ManySteps, explicit and symplectic Euler only); Auto picks ManySteps
// for those integrators up to manyStepsMaxVertices.
enum class StepDispatch { Auto, PerStep, ManySteps };

// Up to this many vertices one work group stepping many times beats two dispatches per step.
// Software (llvmpipe, measured in docs/performance.md, "GPU: work groups, shared-memory tiles,
// many steps per dispatch"): faster up to 16², even at 24², slower from 32² on, because the one
// group runs on one of the CPU's cores while the per-pass dispatches use all of them. Hardware:
// not measured (no GPU was lent); 64² is the estimate there, where one multiprocessor does the
// 4096 vertices of a step in a few µs against ~5 µs per dispatch.
inline constexpr long long manyStepsMaxVertices(bool software) {
    return software ? 24 * 24 : 64 * 64;
}

struct GpuOptions {
    int workGroupX = 16, workGroupY = 16;
    int checkEvery = 64;  // steps between reads of the instability flag
    ForcesKernel forces = ForcesKernel::Global;
    StepDispatch dispatch = StepDispatch::Auto;
    // What set the work group, as an error names it: the app's CLOTH_WORKGROUP, or the default.
    std::string workGroupKey = "work-group size";
};

inline const char* forcesKernelName(ForcesKernel k) {
    return k == ForcesKernel::Tiled ? "tiled" : "global";
}

inline const char* stepDispatchName(StepDispatch d) {
    return d == StepDispatch::PerStep     ? "per-step"
           : d == StepDispatch::ManySteps ? "many-steps"
                                          : "auto";
}

// The process's GPU settings, which the app reads from its environment (README, "Environment")
// and sets once before the first context or shader is made; the library reads no environment.
struct GpuSetup {
    std::string shaderDir;  // "": shaders/ next to the executable, else the source tree's
    int eglDevice = -1;     // >= 0: that EGL device alone (CLOTH_EGL_DEVICE), else hardware first
    // CLOTH_MULTIGRID_TRACE=1: after the first solve's first V-cycle, the multigrid hierarchy
    // summed up level by level on stderr (GpuMultigrid::describe).
    bool traceMultigrid = false;
    // CLOTH_MULTIGRID_CHUNKS: the most chunks a line's solve is cut into (multigrid.glsl
    // chunkVertices), 1 (one chain a line) or 8 … kMultigridChunks; 0 lets multigridChunks pick.
    int multigridChunks = 0;
};
void configureGpu(const GpuSetup& setup);
const GpuSetup& gpuSetup();

}  // namespace cloth
