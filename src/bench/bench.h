// What `clothsim bench accuracy` and `clothsim bench stability` share: flag values (method and
// number lists, the backends to run), the output folder, the CSV file and the gnuplot call.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "backends/solver_factory.h"
#include "model/output_file.h"  // writeWholeFile: the CSV and JSON files
#include "model/scene.h"

namespace cloth::app {

// One backend and arithmetic a benchmark runs on.
struct BenchTarget {
    Backend backend = Backend::Cpu;
    Precision precision = Precision::Double;
    std::string id() const;  // "cpu_double", "gpu_float": the CSV's and the plot's name
};

// The options every bench subcommand takes (see `clothsim bench --help`).
struct BenchCommonOptions {
    std::string scenePath, out = "bench/results", label, backend = "both";
    std::vector<std::string> sets;  // --set KEY.PATH=JSON
    std::vector<Method> methods;
    int threads = 0;  // 0: automatic
    bool quick = false;
    // The backends' settings the app takes from the environment (the CPU's row kernels, the GPU's
    // work group); every solver a bench makes starts from them.
    BackendChoice tuning;
    std::string scriptDir;  // the gnuplot scripts' folder; "" finds bench/ (benchScriptDir)
    BackendChoice base() const {
        BackendChoice c = tuning;
        c.threads = threads;
        return c;
    }
};

// "all" or a comma-separated list of integrator names; InputError naming `flag` otherwise.
std::vector<Method> parseMethods(const std::string& flag, const std::string& value);

// A comma-separated list of positive finite numbers (at least one).
std::vector<double> parsePositiveList(const std::string& flag, const std::string& value);
double parsePositive(const std::string& flag, const std::string& value);

// cpu|gpu|both; the CPU in each of `cpuPrecisions`, the GPU in float.
std::vector<BenchTarget> parseTargets(const std::string& flag, const std::string& value,
                                      const std::vector<Precision>& cpuPrecisions);

// Drops the GPU targets when no GPU context can be made and the user did not ask for the GPU
// alone (`gpuOnly`, then GpuUnavailable propagates: exit 4); says so on stderr.
std::vector<BenchTarget> availableTargets(std::vector<BenchTarget> targets, const Scene& scene,
                                          bool gpuOnly, const BackendChoice& base);

// `base` (threads, tuning) on the target's backend and precision.
BackendChoice choiceFor(const BenchTarget& target, const BackendChoice& base);

// Whether `target` runs `method` on `scene`: the GPU backend refuses (InputError) an integrator it
// has no kernel for; that is said on stderr and the runs are skipped. Other errors propagate.
bool runsMethod(const BenchTarget& target, const Scene& scene, Method method,
                const BackendChoice& base);

// runsMethod asked once per target and integrator: the answer does not change along a sweep.
class MethodSupport {
public:
    bool runs(const BenchTarget& target, const Scene& scene, Method method,
              const BackendChoice& base);

private:
    std::map<std::pair<std::string, Method>, bool> known_;
};

// The bench's scene with its --set overrides; the label defaults to the scene's name.
Scene loadBenchScene(BenchCommonOptions& o);

// Creates `dir` (InputError naming --out when it cannot) and returns dir/name.
std::string outputPath(const std::string& dir, const std::string& name);
// Before a bench runs: --out is a folder it can write into and --label names files in it (not
// empty, no '/', '\' or control characters); InputError naming the flag otherwise.
void checkOutputs(const std::string& dir, const std::string& label);

// A CSV cell: %.6g, or empty for a value that is not finite (nothing non-finite is written).
std::string cell(double value);

// The items joined by `separator`: a CSV row (with its newline added by the caller) or the
// space-separated word lists the plot scripts take.
std::string join(const std::vector<std::string>& items, char separator);
std::string targetIds(const std::vector<BenchTarget>& targets);  // "cpu_double gpu_float"
std::string methodNames(const std::vector<Method>& methods);     // "explicit_euler rk4"

// The curves of a plot, one per (integrator, target) that has rows, as the word lists the plot
// scripts take: series_methods, series_targets, series_colours (the integrator's place in
// kMethods, so that a colour means the same integrator in every plot) and series_styles (1 cpu
// double, 2 cpu float, 3 gpu float: dash and point type); methods, method_colours and
// method_targets (its first curve's) likewise for the integrators alone.
using PlotVars = std::vector<std::pair<std::string, std::string>>;
PlotVars seriesVars(const std::vector<std::pair<Method, BenchTarget>>& curves);

// Runs `script` of benchScriptDir(scriptDir) with gnuplot, once for PNG and once for SVG, into
// `outStem`.png/.svg, with `vars` set as gnuplot string variables. Returns the files written, or
// prints why not (gnuplot missing or failing) on stderr and returns none: the CSV stands on its
// own.
std::vector<std::string> plot(const std::string& scriptDir, const std::string& script,
                              const std::string& outStem, const PlotVars& vars);

// bench/ of the project: `configured` (the app's CLOTH_BENCH_DIR) when not empty, else bench/
// next to the executable, else the source tree's.
std::string benchScriptDir(const std::string& configured);

}  // namespace cloth::app
