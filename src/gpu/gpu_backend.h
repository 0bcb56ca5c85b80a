// The GPU backend as the app sees it (DESIGN.md §1, §3): a Solver computing in float in GLSL
// compute shaders on a headless context, plus what `clothsim info` and `validate` print.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "gpu/gpu_options.h"
#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// Creates the (process-wide, lazily made) headless context if needed. Throws GpuUnavailable,
// InputError (bad work-group override, impossible grid), std::runtime_error (shader problems,
// with file:line).
std::unique_ptr<Solver> makeGpuSolver(const Scene& scene, const GpuOptions& options = {});

// Multi-line: EGL vendor, platform, GL renderer/version, compute limits. Throws GpuUnavailable.
std::string describeGpu();

// Why the GPU backend cannot run this scene with these options (a limit of the device, named:
// checkSceneFits), or nothing. Throws GpuUnavailable.
std::optional<std::string> gpuSceneRefusal(const Scene& scene, const GpuOptions& options);

// GL_RENDERER of the headless context, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)". Throws
// GpuUnavailable.
std::string gpuRendererName();

// Whether that context runs on a software rasteriser (llvmpipe, softpipe, swrast: GpuInfo).
// Throws GpuUnavailable.
bool gpuIsSoftware();

// The #defines this scene compiles to, one line; no GL needed.
std::string describeGpuVariant(const Scene& scene, const GpuOptions& options = {});

}  // namespace cloth
