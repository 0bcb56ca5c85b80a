// The GPU backend as the app sees it (DESIGN.md §1, §3): a Solver computing in float in GLSL
// compute shaders on a headless context, plus what `clothsim info` and `validate` print.
#pragma once

#include <memory>
#include <string>

#include "model/scene.h"
#include "solver/solver.h"
#include "gpu/gpu_options.h"

namespace cloth {

// Creates the (process-wide, lazily made) headless context if needed. Throws GpuUnavailable,
// InputError (bad work-group override, impossible grid), std::runtime_error (shader problems,
// with file:line).
std::unique_ptr<Solver> makeGpuSolver(const Scene& scene, const GpuOptions& options = {});

// Multi-line: EGL vendor, platform, GL renderer/version, compute limits. Throws GpuUnavailable.
std::string describeGpu();

// The #defines this scene compiles to, one line; no GL needed.
std::string describeGpuVariant(const Scene& scene, const GpuOptions& options = {});

}  // namespace cloth
