// clothsim bench speed [SCENE]: steps per second of every backend over grid sizes, beside the
// straightforward one-thread loop (the 1x line) and the machine's measured memory bandwidth.
#include "app/bench_speed.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <thread>

#include "app/bench.h"
#include "app/bench_baseline.h"
#include "app/bench_speed_model.h"
#include "core/errors.h"
#include "core/scene_loader.h"

namespace cloth::app {
namespace {

constexpr const char* kHelp = R"(usage: clothsim bench speed [SCENE] [options]

Times the scene (default scenes/hanging.json) resized to each size x size grid on every backend
asked for (the CPU in float and double, the GPU in float) and on the baseline: the seed's
explicit Euler loop, one thread, double, the 1x line of the speed-ups. After warm-up steps, a
batch of steps is sized to about 50 ms and repeated until 0.3 s and 5 batches have passed; the
median batch is reported. The CPU's triad bandwidth and the GPU's copy-kernel bandwidth are
measured in the same run; achieved GB/s counts the bytes a step must move at least (read and
write each vertex's position and velocity).

options:
  --sizes LIST        grid sides, comma-separated (default 32,64,128,256,512,1024); a size that
                      would not fit in memory is refused
  --backend cpu|gpu|both   where to run (default both; without a GPU, both means cpu)
  --methods LIST      integrators, comma-separated, or all (default the scene's)
  --set KEY.PATH=JSON override a scene key (repeatable)
  --out DIR           output folder (default bench/results)
  --label NAME        file names speed_NAME.csv/.json/.png/.svg (default the scene's name)
  --threads N         CPU threads (default automatic)
  --workgroups LIST   GPU work-group shapes WXxWY, comma-separated (default 16x16); every GPU
                      row is labelled with its variant (shape/forces/dispatch)
  --gpu-forces LIST   global, tiled or both: where the GPU's forces pass reads the neighbours'
                      positions, straight from the buffer or from a shared-memory tile (default
                      global)
  --gpu-dispatch LIST auto, per-step, many-steps, comma-separated: two dispatches per step, or
                      many steps in one work-group dispatch (explicit/symplectic Euler); auto
                      picks many-steps up to 24x24 on llvmpipe, 64x64 on hardware (default
                      auto)
  --check-every N     GPU steps between reads of the instability flag (default 64)
  --pass-times        GPU rows also time one forces pass, one integrate pass and the copy
                      kernel over as many vec4 as the grid has vertices, each alone
  --quick             short timing (5 ms batches, 30 ms per run, small bandwidth arrays)
  --allow-debug       run in a Debug build (refused otherwise: its timings mean nothing)
  --help              this text
)";

struct Options : BenchCommonOptions {  // methods empty: the scene's
    std::vector<int> sizes{32, 64, 128, 256, 512, 1024};
    bool allowDebug = false;
    std::vector<std::pair<int, int>> workGroups{{16, 16}};
    std::vector<ForcesKernel> forces{ForcesKernel::Global};
    std::vector<StepDispatch> dispatches{StepDispatch::Auto};
    int checkEvery = GpuOptions{}.checkEvery;
    bool passTimes = false;

    // Every combination of the GPU flags, in the order given.
    std::vector<GpuOptions> gpuVariants() const {
        std::vector<GpuOptions> all;
        for (const auto& [x, y] : workGroups)
            for (ForcesKernel f : forces)
                for (StepDispatch d : dispatches) all.push_back({x, y, checkEvery, f, d});
        return all;
    }
};

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

// Returns false when --help was asked for.
bool parse(Args& args, Options& o) {
    while (!args.done()) {
        if (args.takeScene(o.scenePath)) continue;
        const std::string f = args.flag();
        if (f == "--help" || f == "-h") return false;
        if (parseCommonFlag(f, args, o)) continue;
        if (f == "--sizes")
            o.sizes = parseSizes(f, args.value(f));
        else if (f == "--allow-debug")
            o.allowDebug = true;
        else if (f == "--workgroups")
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
            o.checkEvery = int(args.positiveInt(f));
        else if (f == "--pass-times")
            o.passTimes = true;
        else
            args.unknown(f);
    }
    if (o.scenePath.empty())
        o.scenePath =
            (std::filesystem::path(benchScriptDir()).parent_path() / "scenes/hanging.json")
                .string();
    return true;
}

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown CPU";
}

std::uint64_t availableMemory() {
    std::ifstream in("/proc/meminfo");
    for (std::string key; in >> key;) {
        std::uint64_t kib = 0;
        in >> kib;
        if (key == "MemAvailable:") return kib * 1024;
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return std::numeric_limits<std::uint64_t>::max();
}

std::vector<std::string> withResolution(std::vector<std::string> sets, int side) {
    sets.push_back("cloth.resolution=[" + std::to_string(side) + "," + std::to_string(side) + "]");
    return sets;
}

struct Timing {
    long stepsPerBatch = 1;
    int batches = 0;
    double secondsPerStep = 0, deviceSecondsPerStep = 0;  // medians
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// Warm-up, then a batch grown by doubling to `batchSeconds`, then batches until `totalSeconds`
// and 5 batches. `step(n)` runs n steps and returns false if the run went unstable; `device()`
// the device's seconds per step of the last call (0 when it has none).
Timing timeSteps(const std::function<bool(long)>& step, const std::function<double()>& device,
                 bool quick) {
    const double batchSeconds = quick ? 0.005 : 0.05, totalSeconds = quick ? 0.03 : 0.3;
    auto clock = [&](long n) {
        const auto t0 = std::chrono::steady_clock::now();
        if (!step(n)) throw std::runtime_error("the run became unstable");
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    Timing t;
    clock(2);  // warm-up: first touch, shader compilation, thread start
    while (clock(t.stepsPerBatch) < batchSeconds && t.stepsPerBatch < (1L << 20))
        t.stepsPerBatch *= 2;
    std::vector<double> wall, dev;
    double total = 0;
    while (t.batches < 5 || (total < totalSeconds && t.batches < 200)) {
        const double s = clock(t.stepsPerBatch);
        total += s;
        wall.push_back(s / double(t.stepsPerBatch));
        dev.push_back(device());
        ++t.batches;
    }
    t.secondsPerStep = median(wall);
    t.deviceSecondsPerStep = median(dev);
    return t;
}

SpeedRow makeRow(int side, const std::string& target, Method method, int threads, const Timing& t,
                 std::size_t minBytesPerVertex, double bandwidth) {
    SpeedRow r;
    r.side = side;
    r.vertices = long(side) * side;
    r.target = target;
    r.method = methodName(method);
    r.threads = threads;
    r.stepsPerBatch = t.stepsPerBatch;
    r.batches = t.batches;
    r.msPerStep = 1e3 * t.secondsPerStep;
    r.deviceMsPerStep = t.deviceSecondsPerStep > 0 ? 1e3 * t.deviceSecondsPerStep : NAN;
    r.stepsPerSecond = 1 / t.secondsPerStep;
    r.vertexStepsPerSecond = double(r.vertices) * r.stepsPerSecond;
    r.minBytesPerStep = double(minBytesPerVertex) * double(r.vertices);
    r.achievedGBps = r.minBytesPerStep / t.secondsPerStep / 1e9;
    r.bandwidthFraction = bandwidth > 0 ? r.achievedGBps / bandwidth : NAN;
    return r;
}

// One row: `target` with `choice` on `sized`, its speed-up over `base`.
SpeedRow timeTarget(const Scene& sized, const BenchTarget& target, const BackendChoice& choice,
                    const Options& o, const SpeedMeta& meta, const SpeedRow& base) {
    const Method m = sized.integrator.method;
    auto solver = makeSolver(sized, choice);
    const Timing st = timeSteps([&](long n) { return !solver->step(n).unstable; },
                                [&] { return deviceSecondsPerStep(*solver); }, o.quick);
    const bool onGpu = target.backend == Backend::Gpu;
    const int cpuThreads =
        o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
    SpeedRow r = makeRow(base.side, target.id(), m, onGpu ? 0 : cpuThreads, st,
                         minStepBytesPerVertex(target.backend, target.precision),
                         onGpu ? meta.copyGBps : meta.triadGBps);
    r.timingSource = deviceTimingSource(*solver);
    r.speedup = r.vertexStepsPerSecond / base.vertexStepsPerSecond;
    // The GPU's own allocation (every buffer it made, bufferBytes()); the CPU's by its model.
    r.bytesPerVertex = onGpu ? double(gpuBufferBytes(*solver)) / double(r.vertices)
                             : double(cpuBytesPerVertex(target.precision, m));
    if (!onGpu) return r;
    r.variant = gpuVariantWord(*solver);
    if (o.passTimes) {
        const GpuPassTimes p = gpuPassTimes(*solver, o.quick ? 3 : 5);
        r.forcesPassMs = 1e3 * p.forces;
        r.integratePassMs = 1e3 * p.integrate;
        r.copyMs = 1e3 * p.copy;
    }
    return r;
}

// A GPU size beyond the device's limits is refused before anything runs, naming the limit.
void refuseGpuSizes(const Options& o) {
    for (int side : o.sizes) {
        const Scene sized = loadScene(o.scenePath, withResolution(o.sets, side));
        for (const GpuOptions& g : o.gpuVariants())
            if (const auto why = gpuSizeRefusal(sized, g))
                throw InputError("command line", "--sizes",
                                 "the GPU cannot hold size " + std::to_string(side) + ": " + *why);
    }
}

}  // namespace

int benchSpeedCommand(Args& args) {
    Options o;
    if (!parse(args, o)) {
        std::fputs(kHelp, stdout);
        return kOk;
    }
    if (const auto why = debugRefusal(CLOTH_BUILD_TYPE, o.allowDebug)) {
        std::fprintf(stderr, "clothsim bench speed: %s\n", why->c_str());
        return kInvalidInput;
    }
    const std::uint64_t memory = availableMemory();
    for (int side : o.sizes)
        if (const auto why = sizeRefusal(side, memory))
            throw InputError("command line", "--sizes", *why);
    const Scene scene = loadScene(o.scenePath, o.sets);
    const std::vector<Method> methods =
        o.methods.empty() ? std::vector<Method>{scene.integrator.method} : o.methods;
    auto targets = parseTargets("--backend", o.backend, {Precision::Float, Precision::Double});
    targets = availableTargets(targets, scene, o.backend == "gpu", o.threads);
    const bool gpu = std::any_of(targets.begin(), targets.end(),
                                 [](const BenchTarget& t) { return t.backend == Backend::Gpu; });

    if (gpu) refuseGpuSizes(o);

    SpeedMeta meta;
    meta.scene = o.scenePath;
    meta.label = o.label.empty() ? scene.name : o.label;
    meta.buildType = CLOTH_BUILD_TYPE;
    meta.cpuModel = cpuModel();
    meta.quick = o.quick;
    const std::size_t bandwidthBytes = std::size_t(o.quick ? 16 : 64) << 20;
    meta.triadGBps = measureTriadBandwidth(bandwidthBytes, o.quick ? 3 : 5) / 1e9;
    meta.copyGBps = gpu ? gpuCopyBandwidth(bandwidthBytes, o.quick ? 3 : 5) / 1e9 : NAN;
    meta.gpuRenderer = gpu ? gpuRenderer() : "";
    std::vector<SpeedRow> rows;
    MethodSupport support;
    for (int side : o.sizes) {
        Scene sized = loadScene(o.scenePath, withResolution(o.sets, side));
        BaselineCloth baseline(sized);
        const Timing bt = timeSteps(
            [&](long n) {
                baseline.step(n);
                return true;
            },
            [] { return 0.0; }, o.quick);
        SpeedRow base =
            makeRow(side, "baseline", Method::ExplicitEuler, 1, bt,
                    minStepBytesPerVertex(Backend::Cpu, Precision::Double), meta.triadGBps);
        base.speedup = 1;
        base.bytesPerVertex = double(kBaselineBytesPerVertex);
        rows.push_back(base);
        for (Method m : methods) {
            sized.integrator.method = m;
            for (const BenchTarget& t : targets) {
                if (!support.runs(t, sized, m, o.threads)) continue;
                if (t.backend != Backend::Gpu) {
                    rows.push_back(timeTarget(sized, t, choiceFor(t, o.threads), o, meta, base));
                    continue;
                }
                for (const GpuOptions& g : o.gpuVariants()) {
                    BackendChoice choice = choiceFor(t, o.threads);
                    choice.gpu = g;
                    try {
                        rows.push_back(timeTarget(sized, t, choice, o, meta, base));
                    } catch (const InputError& e) {  // e.g. many-steps for rk4: said, skipped
                        std::fprintf(stderr, "clothsim bench speed: %dx%d %s %s skipped: %s\n",
                                     side, side, t.id().c_str(), methodName(m), e.what());
                    }
                }
            }
        }
        std::fprintf(stderr, "clothsim bench speed: %dx%d done\n", side, side);
    }
    reportSpeed(o.out, meta, rows);
    return kOk;
}

}  // namespace cloth::app
