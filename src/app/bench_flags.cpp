#include "app/bench_flags.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "model/errors.h"

namespace cloth::app {
namespace {

// Comma-separated items, each one of `names` (InputError naming `flag` otherwise).
template <typename T>
std::vector<T> parseChoices(const std::string& flag, const std::string& value,
                            const std::vector<std::pair<std::string, std::vector<T>>>& names) {
    std::vector<T> out;
    std::stringstream in(value);
    for (std::string item; std::getline(in, item, ',');) {
        const auto it = std::find_if(names.begin(), names.end(),
                                     [&](const auto& n) { return n.first == item; });
        if (it == names.end()) {
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : ", ") + n.first;
            throw InputError(
                "command line", flag,
                "expected a comma-separated list of " + list + ", got '" + value + "'");
        }
        out.insert(out.end(), it->second.begin(), it->second.end());
    }
    if (out.empty()) throw InputError("command line", flag, "expected a value");
    return out;
}

std::vector<std::pair<int, int>> parseWorkGroups(const std::string& flag,
                                                 const std::string& value) {
    std::vector<std::pair<int, int>> shapes;
    std::stringstream in(value);
    for (std::string item; std::getline(in, item, ',');) {
        int x = 0, y = 0;
        char sep = 0, rest = 0;
        if (std::sscanf(item.c_str(), "%d%c%d%c", &x, &sep, &y, &rest) != 3 ||
            (sep != 'x' && sep != 'X') || x < 1 || y < 1 || x > 4096 || y > 4096)
            throw InputError("command line", flag,
                             "expected shapes WXxWY separated by commas, e.g. 8x8,16x16,32x8, "
                             "got '" +
                                 value + "'");
        shapes.push_back({x, y});
    }
    if (shapes.empty()) throw InputError("command line", flag, "expected a value");
    return shapes;
}

}  // namespace

bool parseGpuSweepFlag(const std::string& f, Args& args, GpuSweepOptions& o) {
    if (f == "--workgroups")
        o.workGroups = parseWorkGroups(f, args.value(f));
    else if (f == "--gpu-forces")
        o.forces =
            parseChoices<ForcesKernel>(f, args.value(f),
                                       {{"global", {ForcesKernel::Global}},
                                        {"tiled", {ForcesKernel::Tiled}},
                                        {"both", {ForcesKernel::Global, ForcesKernel::Tiled}}});
    else if (f == "--gpu-dispatch")
        o.dispatches = parseChoices<StepDispatch>(f, args.value(f),
                                                  {{"auto", {StepDispatch::Auto}},
                                                   {"per-step", {StepDispatch::PerStep}},
                                                   {"many-steps", {StepDispatch::ManySteps}}});
    else if (f == "--check-every")
        o.checkEvery = args.positiveInt32(f);
    else if (f == "--pass-times")
        o.passTimes = true;
    else
        return false;
    return true;
}

std::vector<int> parseSizes(const std::string& flag, const std::string& value) {
    std::vector<int> sizes;
    for (double x : parsePositiveList(flag, value)) {
        if (x != std::floor(x) || x < 2 || x > 65535)
            throw InputError("command line", flag,
                             "expected whole grid sides from 2 to 65535, got '" + value + "'");
        sizes.push_back(int(x));
    }
    return sizes;
}

bool parseCommonFlag(const std::string& f, Args& args, BenchCommonOptions& o) {
    if (f == "--backend")
        o.backend = args.value(f);
    else if (f == "--methods")
        o.methods = parseMethods(f, args.value(f));
    else if (f == "--set")
        addSet(o.sets, args.value(f));
    else if (f == "--out")
        o.out = args.value(f);
    else if (f == "--label")
        o.label = args.value(f);
    else if (f == "--threads")
        o.threads = args.positiveInt32(f);
    else if (f == "--quick")
        o.quick = true;
    else
        return false;
    return true;
}

}  // namespace cloth::app
