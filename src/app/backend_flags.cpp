#include "app/backend_flags.h"

#include <cstdio>

namespace cloth::app {

bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice) {
    if (flag == "--backend")
        parseBackend(flag, args.value(flag), choice);
    else if (flag == "--precision")
        choice.precision = parsePrecision(flag, args.value(flag));
    else if (flag == "--threads")
        choice.threads = args.positiveInt32(flag);
    else
        return false;
    return true;
}

bool RunFlags::take(const std::string& flag, Args& args) {
    precisionGiven |= flag == "--precision";
    if (parseBackendFlag(flag, args, backend)) return true;
    if (flag != "--set") return false;
    addSet(sets, args.value(flag), &notices);
    return true;
}

void RunFlags::finish(bool quiet) const {
    refuseGpuDouble(backend, precisionGiven);
    if (quiet) return;
    for (const std::string& notice : notices)
        std::fprintf(stderr, "clothsim: note: %s\n", notice.c_str());
}

void settleBackendAndSay(BackendChoice& choice, const Scene& scene, bool doubleAsked, bool quiet) {
    const std::string line = settleBackend(choice, scene, doubleAsked);
    if (!quiet && !line.empty()) std::fprintf(stderr, "clothsim: %s\n", line.c_str());
}

}  // namespace cloth::app
