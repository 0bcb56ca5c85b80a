// The backend flags `run`, `render` and `view` share, and the environment variables that tune a
// backend: the app reads them here and hands the libraries plain options.
#pragma once

#include <string>
#include <vector>

#include "app/cli.h"
#include "backends/solver_factory.h"

namespace cloth::app {

// --backend cpu|gpu|auto, --precision float|double, --threads N: true when `flag` was one of
// them (its value then taken from `args` into `choice`).
bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice);

// The GPU backend computes in float: a command that runs one backend refuses --precision double
// with --backend gpu (InputError naming --precision) rather than compute in float silently.
// `precisionGiven`: --precision was on the command line (the default double is no request).
void refuseGpuDouble(const BackendChoice& choice, bool precisionGiven);

// The flags of a command that runs one backend (run, render, view): the backend flags and --set.
// take() is true when `flag` was one of them; finish() refuses their bad combinations (run,
// render).
struct RunFlags {
    BackendChoice& backend;
    std::vector<std::string>& sets;
    bool precisionGiven = false;

    bool take(const std::string& flag, Args& args);
    void finish() const { refuseGpuDouble(backend, precisionGiven); }
    // --precision double was asked for: --backend auto then picks the CPU.
    bool doubleAsked() const { return precisionGiven && backend.precision == Precision::Double; }
};

// Settles `choice` for `scene` (backends/solver_factory.h settleBackend) and, unless `quiet`, says
// on stderr which backend --backend auto picked and why, or that --backend gpu runs on a software
// rasteriser.
void settleBackendAndSay(BackendChoice& choice, const Scene& scene, bool doubleAsked, bool quiet);

// --backend cpu|gpu|auto into `choice`; auto leaves the pick to settleBackend, once the scene is
// known.
void parseBackend(const std::string& flag, const std::string& value, BackendChoice& choice);
Precision parsePrecision(const std::string& flag, const std::string& value);

// The choice as the environment tunes it (README, "Environment"): CLOTH_CPU_ISA picks the CPU's
// row kernels, CLOTH_WORKGROUP=WXxWY the GPU's work group. Throws InputError naming the variable
// for a bad value.
BackendChoice backendChoiceFromEnvironment();

// The process's GPU settings from CLOTH_SHADER_DIR and CLOTH_EGL_DEVICE (InputError naming the
// variable for a bad value); main() hands them to the GPU library before any command runs.
GpuSetup gpuSetupFromEnvironment();

// CLOTH_BENCH_DIR: the bench plots' gnuplot scripts, or "" (bench/ found by the bench library).
std::string benchDirFromEnvironment();

}  // namespace cloth::app
