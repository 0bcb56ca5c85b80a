#include "app/backend_flags.h"

namespace cloth::app {

bool parseBackendFlag(const std::string& flag, Args& args, BackendChoice& choice) {
    if (flag == "--backend")
        choice.backend = parseBackend(flag, args.value(flag));
    else if (flag == "--precision")
        choice.precision = parsePrecision(flag, args.value(flag));
    else if (flag == "--threads")
        choice.threads = int(args.positiveInt(flag));
    else
        return false;
    return true;
}

bool RunFlags::take(const std::string& flag, Args& args) {
    precisionGiven |= flag == "--precision";
    if (parseBackendFlag(flag, args, backend)) return true;
    if (flag != "--set") return false;
    addSet(sets, args.value(flag));
    return true;
}

}  // namespace cloth::app
