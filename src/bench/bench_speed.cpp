// clothsim bench speed [SCENE]: steps per second of every backend over grid sizes, beside the
// straightforward one-thread loop (the 1x line) and the machine's measured memory bandwidth.
#include "bench/bench_speed.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <sstream>
#include <thread>

#include "bench/bench.h"
#include "bench/bench_baseline.h"
#include "bench/bench_features.h"
#include "bench/bench_peer.h"
#include "bench/bench_speed.h"
#include "bench/bench_speed_gpu.h"
#include "bench/bench_speed_model.h"
#include "bench/bench_speed_timing.h"
#include "model/errors.h"
#include "model/stability.h"
#include "scene/scene_loader.h"

namespace cloth::app {
namespace {

using Options = SpeedOptions;

// What one run of the command shares between sizes.
struct Sweep {
    const Options& o;
    const SpeedMeta& meta;
    std::vector<Method> methods;
    std::vector<BenchTarget> targets;
    int cpuThreads = 1;
    MethodSupport support;
    std::set<int> gpuSkipped;  // default sizes the GPU cannot hold
};

SpeedRow timeBaseline(const Scene& sized, int side, const Sweep& w) {
    BaselineCloth baseline(sized);
    const Timing t = timeSteps(
        [&](long n) {
            baseline.step(n);
            return true;
        },
        [] { return 0.0; }, w.o.quick);
    SpeedRow r =
        makeRow(side, "baseline", methodName(Method::ExplicitEuler), 1, t,
                double(minStepBytesPerVertex(Backend::Cpu, Precision::Double)), w.meta.triadGBps);
    r.bytesPerVertex = double(kBaselineBytesPerVertex);
    r.dt = sized.integrator.dt;
    return r;
}

// One row: `target` with `choice` on `scene` at this size.
SpeedRow timeTarget(const Scene& scene, int side, const BenchTarget& t, const BackendChoice& choice,
                    const std::string& features, const Sweep& w) {
    const Method m = scene.integrator.method;
    auto solver = makeSolver(scene, choice);
    const bool onGpu = t.backend == Backend::Gpu;
    Timing st;
    try {
        st = timeSteps([&](long n) { return !solver->step(n).unstable; },
                       [&] { return solver->deviceReport().secondsPerStep; }, w.o.quick);
    } catch (const BecameUnstable&) {  // a row without a time, said on stderr; the sweep goes on
        std::fprintf(stderr,
                     "clothsim bench speed: %s %s at %dx%d became unstable after %ld steps at "
                     "dt %g s: not timed (validate prints the stable dt)\n",
                     t.id().c_str(), methodName(m), side, side, solver->stepsDone(),
                     scene.integrator.dt);
        SpeedRow r =
            makeRow(side, t.id(), methodName(m), onGpu ? 0 : w.cpuThreads, Timing{}, NAN, NAN);
        r.msPerStep = r.stepsPerSecond = r.vertexStepsPerSecond = NAN;
        r.features = features;
        r.dt = scene.integrator.dt;
        r.status = "unstable";
        return r;
    }
    SpeedRow r = makeRow(side, t.id(), methodName(m), onGpu ? 0 : w.cpuThreads, st,
                         double(minStepBytesPerVertex(t.backend, t.precision)),
                         onGpu ? w.meta.copyGBps : w.meta.triadGBps);
    r.features = features;
    r.dt = scene.integrator.dt;
    const DeviceReport device = solver->deviceReport();
    r.timingSource = device.timing;
    // The GPU's own allocation (every buffer it made, bufferBytes()); the CPU's by its model.
    r.bytesPerVertex =
        onGpu ? double(device.bytes) / double(r.vertices)
              : double(cpuBytesPerVertex(t.precision, m, scene.integrator.preconditioner,
                                         !scene.colliders.empty(),
                                         resolveCpuIsa(choice.isa) != CpuIsa::Scalar,
                                         scene.anyFriction(), scene.integrator.vbdTranslates()));
    if (!onGpu) return r;
    // The variant as asked (one curve per variant in the plot), the dispatch as run.
    r.variant = device.variant + "/" + stepDispatchName(choice.gpu.dispatch);
    r.dispatch = device.dispatch;
    if (w.o.gpuSweep.passTimes) {
        const GpuPassTimes p = gpuPassTimes(*solver, w.o.quick ? 3 : 5);
        r.forcesPassMs = 1e3 * p.forces;
        r.integratePassMs = 1e3 * p.integrate;
        r.copyMs = 1e3 * p.copy;
    }
    return r;
}

// Every target and integrator on `scene` (the declared scene or its all-features twin).
void timeBackends(Scene scene, int side, const std::string& features, Sweep& w,
                  std::vector<SpeedRow>& rows) {
    for (Method m : w.methods) {
        scene.integrator.method = m;
        for (const BenchTarget& t : w.targets) {
            if (t.backend == Backend::Gpu && w.gpuSkipped.count(side)) continue;
            if (!w.support.runs(t, scene, m, w.o.base())) continue;
            if (t.backend != Backend::Gpu) {
                rows.push_back(timeTarget(scene, side, t, choiceFor(t, w.o.base()), features, w));
                continue;
            }
            for (const GpuOptions& g : w.o.gpuSweep.variants()) {
                BackendChoice choice = choiceFor(t, w.o.base());
                choice.gpu = g;
                try {
                    rows.push_back(timeTarget(scene, side, t, choice, features, w));
                } catch (const InputError& e) {  // e.g. many-steps for rk4: said, skipped
                    std::fprintf(stderr, "clothsim bench speed: %dx%d %s %s skipped: %s\n", side,
                                 side, t.id().c_str(), methodName(m), e.what());
                }
            }
        }
    }
}

// The peer on the declared scene, timed like ours, then checked: a run that left its cloth
// (a node not finite, or 5 extents away) is reported as exploded, one in which nothing moved
// as frozen, either without a time.
SpeedRow timePeer(Scene sized, int side, const Sweep& w, std::string& description) {
    if (w.o.peerDt > 0) sized.integrator.dt = w.o.peerDt;
    auto peer = makePeerCloth(w.o.peer, sized);
    description = peer->describe();
    const std::vector<glm::dvec3> start = peer->positions();
    const Timing t = timeSteps(
        [&](long n) {
            peer->step(n);
            return true;
        },
        [] { return 0.0; }, w.o.quick);
    SpeedRow r = makeRow(side, "peer_" + w.o.peer, peer->method(), 1, t, NAN, NAN);
    r.bytesPerVertex = peer->bytesPerVertex();
    r.dt = sized.integrator.dt;
    const std::vector<glm::dvec3> end = peer->positions();
    std::optional<std::string> why = peerExplosion(start, end, sized.grid().extent());
    r.status = why ? "exploded" : "ok";
    if (!why && glm::length(sized.gravity) > 0 && peerFrozen(start, end)) {
        why = "no node moved";
        r.status = "frozen";
    }
    if (why) {
        std::fprintf(stderr, "clothsim bench speed: the %s peer %s at %dx%d (%s): not timed\n",
                     w.o.peer.c_str(), r.status.c_str(), side, side, why->c_str());
        r.msPerStep = r.stepsPerSecond = r.vertexStepsPerSecond = NAN;
    }
    return r;
}

// Every row's vertex-steps/s over the peer's at its size, and the speed-ups over the baseline's.
void ratios(std::vector<SpeedRow>& rows) {
    for (SpeedRow& r : rows)
        for (const SpeedRow& q : rows) {
            if (q.side != r.side) continue;
            if (q.target == "baseline") r.speedup = r.vertexStepsPerSecond / q.vertexStepsPerSecond;
            if (q.target.rfind("peer_", 0) == 0 && q.status == "ok")
                r.peerRatio = r.vertexStepsPerSecond / q.vertexStepsPerSecond;
        }
}

std::vector<std::string> withResolution(std::vector<std::string> sets, int side) {
    sets.push_back("cloth.resolution=[" + std::to_string(side) + "," + std::to_string(side) + "]");
    return sets;
}

// The scene at side × side. A material resized is the same cloth, finer, and its stable Δt
// shrinks with the cells: unless the command line sets integrator.dt, each size steps at the
// fraction of its own bound (model/stability.h stableDt) that the scene's Δt is of the bound at
// the scene's resolution.
Scene sizedScene(const Options& o, const Scene& declared, int side) {
    Scene s = loadScene(o.scenePath, withResolution(o.sets, side));
    const bool dtSet = std::any_of(o.sets.begin(), o.sets.end(), [](const std::string& set) {
        return set.rfind("integrator.dt=", 0) == 0;
    });
    if (!s.material || dtSet) return s;
    const double scale = stableDt(s) / stableDt(declared);
    if (std::isfinite(scale) && scale > 0) s.integrator.dt = declared.integrator.dt * scale;
    return s;
}

// A GPU size beyond the device's limits, checked before anything runs: refused naming the limit
// when the user listed it (--sizes), else (the default sizes, "as far as memory allows") its GPU
// rows are skipped with that reason on stderr. Returns the sizes to skip.
std::set<int> gpuSizesBeyondDevice(const Options& o) {
    std::set<int> skipped;
    for (int side : o.sizes) {
        const Scene sized = loadScene(o.scenePath, withResolution(o.sets, side));
        for (const GpuOptions& g : o.gpuSweep.variants()) {
            const auto why = gpuRefusal(sized, g);
            if (!why) continue;
            // A work group past the device's limits fails at any size: that flag is named.
            if (why->find("work-group") != std::string::npos)
                throw InputError("command line", "--workgroups", *why);
            const std::string message =
                "the GPU cannot hold size " + std::to_string(side) + ": " + *why;
            if (o.sizesGiven) throw InputError("command line", "--sizes", message);
            std::fprintf(stderr, "clothsim bench speed: %s; its GPU rows are skipped\n",
                         message.c_str());
            skipped.insert(side);
            break;
        }
    }
    return skipped;
}

}  // namespace

int runBenchSpeed(const SpeedOptions& options) {
    SpeedOptions o = options;
    if (const auto why = debugRefusal(CLOTH_BUILD_TYPE, o.allowDebug)) {
        std::fprintf(stderr, "clothsim bench speed: %s\n", why->c_str());
        return kInvalidInput;
    }
    const std::uint64_t memory = availableMemory();
    std::vector<int> fitting;
    for (int side : o.sizes) {
        const auto why = sizeRefusal(side, memory);
        if (why && o.sizesGiven) throw InputError("command line", "--sizes", *why);
        if (why)
            std::fprintf(stderr, "clothsim bench speed: %s; skipped\n", why->c_str());
        else
            fitting.push_back(side);
    }
    o.sizes = fitting;
    const Scene scene = loadScene(o.scenePath, o.sets);
    checkOutputs(o.out, o.label.empty() ? scene.name : o.label);  // before anything runs
    if (!o.peer.empty() && scene.material)
        throw InputError("command line", "--peer",
                         "the " + o.peer +
                             " peer maps the per-vertex form (cloth.mass, springs, "
                             "damping) and " +
                             o.scenePath +
                             " gives a material: use "
                             "bench/hanging_per_vertex.json");
    auto targets = parseTargets("--backend", o.backend, {Precision::Float, Precision::Double});
    targets = availableTargets(targets, scene, o.backend == "gpu", o.base());
    const bool gpu = std::any_of(targets.begin(), targets.end(),
                                 [](const BenchTarget& t) { return t.backend == Backend::Gpu; });

    const std::set<int> gpuSkipped = gpu ? gpuSizesBeyondDevice(o) : std::set<int>{};

    SpeedMeta meta;
    meta.scene = o.scenePath;
    meta.label = o.label.empty() ? scene.name : o.label;
    meta.scriptDir = o.scriptDir;
    meta.buildType = CLOTH_BUILD_TYPE;
    meta.cpuModel = cpuModel();
    meta.quick = o.quick;
    const std::size_t bandwidthBytes = std::size_t(o.quick ? 16 : 64) << 20;
    meta.triadGBps = measureTriadBandwidth(bandwidthBytes, o.quick ? 3 : 5) / 1e9;
    meta.copyGBps = gpu ? gpuCopyBandwidth(bandwidthBytes, o.quick ? 3 : 5) / 1e9 : NAN;
    meta.gpuRenderer = gpu ? gpuRenderer() : "";

    Sweep w{o,
            meta,
            o.methods.empty() ? std::vector<Method>{scene.integrator.method} : o.methods,
            targets,
            o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency())),
            {},
            gpuSkipped};
    std::vector<SpeedRow> rows;
    for (int side : o.sizes) {
        const Scene sized = sizedScene(o, scene, side);
        rows.push_back(timeBaseline(sized, side, w));
        if (o.features != FeatureSet::All) timeBackends(sized, side, "declared", w, rows);
        if (o.features != FeatureSet::Declared)
            timeBackends(withInertFeatures(sized), side, "all", w, rows);
        if (!o.peer.empty() && side <= kPeerMaxSide)
            rows.push_back(timePeer(sized, side, w, meta.peer));
        else if (!o.peer.empty())
            std::fprintf(stderr, "clothsim bench speed: no %s peer at %dx%d (above %d)\n",
                         o.peer.c_str(), side, side, kPeerMaxSide);
        std::fprintf(stderr, "clothsim bench speed: %dx%d done\n", side, side);
    }
    ratios(rows);
    reportSpeed(o.out, meta, rows);
    return kOk;
}

}  // namespace cloth::app
