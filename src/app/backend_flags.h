// The backend flags `run`, `render` and `view` share: the app reads them here and hands the
// libraries plain options (the names and the environment: app/backend_options.h).
#pragma once

#include <string>
#include <vector>

#include "app/backend_options.h"
#include "app/cli.h"
#include "backends/solver_factory.h"

namespace cloth::app {

// --backend cpu|gpu|auto, --precision float|double, --threads N: true when `flag` was one of
// them (its value then taken from `args` into `choice`).
bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice);

// The flags of a command that runs one backend (run, render, view): the backend flags and --set.
// take() is true when `flag` was one of them; finish() refuses their bad combinations and, unless
// `quiet`, prints the notes on --set replacing an earlier --set.
struct RunFlags {
    BackendChoice& backend;
    std::vector<std::string>& sets;
    bool precisionGiven = false;
    std::vector<std::string> notices{};

    bool take(const std::string& flag, Args& args);
    void finish(bool quiet = false) const;
    // --precision double was asked for: --backend auto then picks the CPU.
    bool doubleAsked() const { return precisionGiven && backend.precision == Precision::Double; }
};

// Settles `choice` for `scene` (backends/solver_factory.h settleBackend) and, unless `quiet`, says
// on stderr which backend --backend auto picked and why, or that --backend gpu runs on a software
// rasteriser.
void settleBackendAndSay(BackendChoice& choice, const Scene& scene, bool doubleAsked, bool quiet);

}  // namespace cloth::app
