// The backend flags `run`, `render` and `view` share; the names they take and the environment
// are read in app/backend_options.h.
#pragma once

#include <string>
#include <vector>

#include "app/backend_options.h"
#include "app/cli.h"
#include "backends/solver_factory.h"

namespace cloth::app {

// --backend cpu|gpu, --precision float|double, --threads N: true when `flag` was one of them
// (its value then taken from `args` into `choice`).
bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice);

// The flags of a command that runs one backend (run, render): the backend flags and --set.
// take() is true when `flag` was one of them; finish() refuses their bad combinations.
struct RunFlags {
    BackendChoice& backend;
    std::vector<std::string>& sets;
    bool precisionGiven = false;

    bool take(const std::string& flag, Args& args);
    void finish() const { refuseGpuDouble(backend, precisionGiven); }
};

}  // namespace cloth::app
