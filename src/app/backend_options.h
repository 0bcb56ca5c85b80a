// How a front end chooses a backend: the backends' names and the environment variables that tune
// them (README, "Environment"). Both front ends, the clothsim executable and the Python module
// (python/), read them here and hand the libraries plain options; no library reads the
// environment.
#pragma once

#include <string>

#include "backends/solver_factory.h"

namespace cloth::app {

// "cpu", "gpu" or "auto" into `choice` (auto leaves the pick to settleBackend, once the scene is
// known); "float" or "double". Anything else is an InputError naming `flag`.
void parseBackend(const std::string& flag, const std::string& value, BackendChoice& choice);
Precision parsePrecision(const std::string& flag, const std::string& value);

// The GPU backend computes in float: a command that runs one backend refuses --precision double
// with --backend gpu (InputError naming --precision) rather than compute in float silently
// (--backend auto then picks the CPU).
// `precisionGiven`: --precision was on the command line (the default double is no request).
void refuseGpuDouble(const BackendChoice& choice, bool precisionGiven);

// The choice as the environment tunes it (README, "Environment"): CLOTH_CPU_ISA picks the CPU's
// row kernels, CLOTH_WORKGROUP=WXxWY the GPU's work group. Throws InputError naming the variable
// for a bad value.
BackendChoice backendChoiceFromEnvironment();

// The process's GPU settings from CLOTH_SHADER_DIR and CLOTH_EGL_DEVICE (InputError naming the
// variable for a bad value); handed to the GPU library before any solver or context is made.
GpuSetup gpuSetupFromEnvironment();

// CLOTH_BENCH_DIR: the bench plots' gnuplot scripts, or "" (bench/ found by the bench library).
std::string benchDirFromEnvironment();

}  // namespace cloth::app
