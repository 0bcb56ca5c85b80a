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
  --quick             short timing (5 ms batches, 30 ms per run, small bandwidth arrays)
  --allow-debug       run in a Debug build (refused otherwise: its timings mean nothing)
  --help              this text
)";

struct Options : BenchCommonOptions {  // methods empty: the scene's
    std::vector<int> sizes{32, 64, 128, 256, 512, 1024};
    bool allowDebug = false;
};

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
    const int cpuThreads =
        o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));

    std::vector<SpeedRow> rows;
    MethodSupport support;
    for (int side : o.sizes) {
        std::vector<std::string> sets = o.sets;
        sets.push_back("cloth.resolution=[" + std::to_string(side) + "," + std::to_string(side) +
                       "]");
        Scene sized = loadScene(o.scenePath, sets);
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
                auto solver = makeSolver(sized, choiceFor(t, o.threads));
                const Timing st = timeSteps([&](long n) { return !solver->step(n).unstable; },
                                            [&] { return deviceSecondsPerStep(*solver); }, o.quick);
                const bool onGpu = t.backend == Backend::Gpu;
                SpeedRow r = makeRow(side, t.id(), m, onGpu ? 0 : cpuThreads, st,
                                     minStepBytesPerVertex(t.backend, t.precision),
                                     onGpu ? meta.copyGBps : meta.triadGBps);
                r.timingSource = deviceTimingSource(*solver);
                r.speedup = r.vertexStepsPerSecond / base.vertexStepsPerSecond;
                r.bytesPerVertex = onGpu ? double(gpuBufferBytes(*solver)) / double(r.vertices)
                                         : double(cpuBytesPerVertex(t.precision, m));
                rows.push_back(r);
            }
        }
        std::fprintf(stderr, "clothsim bench speed: %dx%d done\n", side, side);
    }
    reportSpeed(o.out, meta, rows);
    return kOk;
}

}  // namespace cloth::app
