// Long runs, float GPU against double CPU (docs/gpu.md "Error bound for long runs"): every
// shipped scene for 100 000 steps on both (fewer for the costliest, stepsFor), compared every
// 1000 steps by what a user compares.
//
// Once contact, folds or flapping amplify rounding, two correct runs put a fold or a contact edge
// in different cells and their per-vertex positions separate. Each run resolves such a line to one
// cell h = max(du, dv) of the continuum cloth's, so two runs differ by at most two "line moves":
// a line of P vertices (P = the grid's border vertices, the longest line a convex fold or contact
// edge can form on the cloth) moved by h. The bounds are twice an observable's change under one
// line move; with N vertices, m the heaviest vertex's mass, g = |g|, K the softer structural
// stiffness, L the shorter structural rest length and μ_f the largest friction coefficient of the
// colliders:
//   mean height     |Δȳ| ≤ 2 P h / N                   (P vertices lifted by h)
//   energy          |ΔE| ≤ 2 (m g P h + (P/N)(K + S))  (their weight lifted by h, and their
//                                                      share of kinetic and spring energy)
//   largest strain  |Δε| ≤ 2 ((P/N) ε + μ_f P m g/(K L))
//                                                      (their share of the load on the most
//                                                      strained spring, and the tension their
//                                                      friction can lock in)
//   contact count   |ΔC| ≤ 2 P                         (each of them touching in one run)
// K + S and ε are the larger of the two runs', and the strain bound adds 2·u·R/L, the strain
// float positions resolve (u = 2^-24, R = max |p|).
//
// A cloth that has not come to rest adds its motion. Under air drag alone (a material's
// air_damping, 0.5–1.3 s⁻¹) a sheet swings for seconds and a flag flutters for as long as the
// wind blows; once two runs have separated they are at different phases of the same motion.
//  - The largest strain, one spring's at a pin or an edge, peaks with the swing's dynamic load:
//    its bound adds the range (max − min) the double run's strain covered over its last
//    kMotionWindow samples (10 000 steps, 3–4 s), zero for a cloth at rest.
//  - A wind-driven scene (flag, windsock) never comes to rest: its four observables are
//    compared as time averages over the run past its first kMotionWindow samples, bounded by
//    the line moves (the largest bound of any sample) plus kSigmas standard errors of the
//    difference of the two averages (batch means over kMotionWindow samples).
// A chain (one row of vertices) with neither
// colliders nor wind has nothing to fold, buckle or touch: there the per-vertex envelope
// E(n) = 4·√(n + 1)·u·R/extent of the smooth regime (gpu_divergence_test.cpp) holds for the whole
// run as well. And wherever the double run is stable the float run must be: no instability
// report, no spring beyond max_strain.
#include <algorithm>
#include <cctype>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "gpu/gpu_test_support.h"
#include "model/collider_pose.h"
#include "solver/diagnostics.h"

namespace cloth::test {
namespace {

constexpr long kSteps = 100000;

// The run of a scene: kSteps, but fewer where a material's step (its bending force, on the GPU
// too) costs three times the per-vertex scenes' and the cloth has long come to rest: cape 40 000
// steps (16 s, the figure turned twice), drape and table 50 000 (20 s), hanging 50 000 (15 s).
// The wind-driven flag and windsock keep kSteps (40 s, 32 s): their time averages need them.
long stepsFor(const std::string& name) {
    if (name == "cape") return 40000;
    if (name == "drape" || name == "table" || name == "hanging") return 50000;
    return kSteps;
}
constexpr long kSampleEvery = 1000;
constexpr double kLineMoves = 2;                   // one per run, see above
constexpr double kUnitRoundoff = FLT_EPSILON / 2;  // u = 2^-24
constexpr double kEnvelopeFactor = 4;              // gpu_divergence_test.cpp, docs/gpu.md
// A vertex touches a collider when it lies within this fraction of a cell of the collider's
// offset surface: 5·10⁻⁶ m on the shipped scenes, 40 times the float rounding of a position
// (u·2 m), far below anything the grid resolves.
constexpr double kContactBand = 1e-4;
// The samples (of kSampleEvery steps) over which a still-moving cloth's motion is measured.
constexpr std::size_t kMotionWindow = 10;
// Standard errors two time averages of a wind-driven scene may differ by, beyond the line moves.
constexpr double kSigmas = 4;

// The shipped scenes, by file name without ".json", sorted: a scene added later is compared too,
// except the pile and the fold. Compared without self-collision (its threshold decisions part
// the backends' trajectories within steps, gpu_self_collision_test.cpp), they crumple through
// themselves, a chaotic motion no observable of which the two backends share for long (the
// pile's mean height differed by 0.014 m at step 2000).
std::vector<std::string> shippedSceneNames() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(CLOTH_SOURCE_DIR "/scenes"))
        if (entry.path().extension() == ".json" && entry.path().stem() != "pile" &&
            entry.path().stem() != "fold")
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

struct Observables {
    double energy = 0;            // kinetic + gravity + spring [J] (solver/diagnostics.h)
    double kineticAndSpring = 0;  // K + S [J]
    double meanHeight = 0;        // mean of ⟨p, −ĝ⟩, the centre of mass's height [m]
    double strain = 0;            // maxStrain: the largest structural stretch
    long contacts = 0;            // vertices within the contact band of a collider
};

// Up: −ĝ, or y where there is no gravity.
glm::dvec3 upOf(const Scene& scene) {
    const double g = glm::length(scene.gravity);
    return g > 0 ? -scene.gravity / g : glm::dvec3(0, 1, 0);
}

long contactCount(const Scene& scene, const SimState& s, double t) {
    const Grid grid = scene.grid();
    const double band = kContactBand * std::max(grid.du, grid.dv);
    std::vector<bool> touching(s.positions.size(), false);
    for (const Collider& c : scene.colliders) {
        const ShapeD shape = posedShape(c, t);  // φ − h as tests/support/shipped_outcomes.h
        for (size_t k = 0; k < s.positions.size(); ++k) {
            const double phi =
                std::visit([&](const auto& sh) { return contact(sh, s.positions[k]).phi; }, shape);
            if (phi - c.thickness <= band) touching[k] = true;
        }
    }
    return long(std::count(touching.begin(), touching.end(), true));
}

Observables observe(const Scene& scene, const SimState& s, double t) {
    Observables o;
    const Energy e = energy(scene, s);
    o.energy = e.total();
    o.kineticAndSpring = e.kinetic + e.spring;
    const glm::dvec3 up = upOf(scene);
    for (const glm::dvec3& p : s.positions) o.meanHeight += glm::dot(p, up);
    o.meanHeight /= double(s.positions.size());
    o.strain = maxStrain(scene, s);
    o.contacts = contactCount(scene, s, t);
    return o;
}

// What one line move (P vertices moved by one cell h) changes, in each observable's units.
struct LineMove {
    double meanHeight = 0;  // P h / N [m]
    double lift = 0;        // m g P h: the line's weight lifted by h [J]
    double share = 0;       // P / N: the line's share of K + S, and of a spring's load
    double friction = 0;    // μ_f P m g / (K L): strain friction can lock in
    double contacts = 0;    // P
    double shortest = 0;    // L [m]; 0 where the scene has no structural springs
};

LineMove lineMoveOf(const Scene& scene) {
    const Grid grid = scene.grid();
    const double n = double(grid.count());
    const double border = n - double(std::max(grid.nu - 2, 0)) * double(std::max(grid.nv - 2, 0));
    const double h = std::max(grid.du, grid.dv);
    const double shortest = grid.du > 0 && grid.dv > 0 ? std::min(grid.du, grid.dv) : h;
    // m: the heaviest vertex (a material's interior one; the per-vertex form's one mass).
    double mass = 0;
    for (int j = 0; j < grid.nv; ++j)
        for (int i = 0; i < grid.nu; ++i) mass = std::max(mass, scene.vertexMass(i, j));
    const double weight = mass * glm::length(scene.gravity);  // m g [N]
    double mu = 0;                                            // μ_f
    for (const Collider& c : scene.colliders) mu = std::max(mu, c.friction);
    // K: the softer structural spring (a material's K along u and along v can differ).
    double stiffness = 0;
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s) {
        const double k = scene.slotStiffness(int(s));
        if (kSpringOffsets[s].family == Family::Structural && k > 0)
            stiffness = stiffness > 0 ? std::min(stiffness, k) : k;
    }
    LineMove l;
    l.meanHeight = border * h / n;
    l.lift = weight * border * h;
    l.share = border / n;
    l.friction = stiffness > 0 ? mu * border * weight / (stiffness * shortest) : 0;
    l.contacts = border;
    l.shortest = stiffness > 0 ? shortest : 0;
    return l;
}

// A chain of vertices with nothing to touch and no wind: no fold, no buckling, no contact.
bool isSmoothChain(const Scene& scene) {
    const Grid g = scene.grid();
    return (g.nu == 1 || g.nv == 1) && scene.colliders.empty() && !scene.wind;
}

enum Observable { kMeanHeight, kEnergy, kStrain, kContacts, kEnvelope, kObservables };
constexpr const char* kNames[kObservables] = {"mean height", "energy", "strain", "contacts",
                                              "per-vertex envelope"};

// One sample: |difference|, its bound, and their ratio per observable (0 where none applies).
struct Sample {
    long step = 0;
    bool averaged = false;  // time averages over the run (a wind-driven scene), not one state
    double observed[kObservables] = {}, bound[kObservables] = {}, ratio[kObservables] = {};
    void set(Observable o, double difference, double limit) {
        observed[o] = difference;
        bound[o] = limit;
        ratio[o] = difference == 0 ? 0 : difference / limit;
    }
};

struct Comparison {
    std::vector<Sample> samples;
    double worst[kObservables] = {};
    std::vector<std::string> stability;  // where the float run left the double run's stability
    double gpuSeconds = 0, cpuSeconds = 0;
};

// How far the double run's largest strain has ranged (max − min) over its last kMotionWindow
// samples, `recent`: the motion of a cloth still swinging.
double strainMotion(const std::deque<Observables>& recent) {
    double lo = recent.front().strain, hi = lo;
    for (const Observables& o : recent) {
        lo = std::min(lo, o.strain);
        hi = std::max(hi, o.strain);
    }
    return hi - lo;
}

// `a` and `b` are the float and double runs' observables at this sample, `motion` the double
// run's strainMotion (0: the line moves alone).
Sample compareAt(const Scene& scene, const Observables& a, const Observables& b, double motion,
                 const SimState& gpu, const SimState& cpu, long step, double radius) {
    const LineMove l = lineMoveOf(scene);
    const double share = std::max(a.kineticAndSpring, b.kineticAndSpring);
    Sample s;
    s.step = step;
    s.set(kMeanHeight, std::abs(a.meanHeight - b.meanHeight), kLineMoves * l.meanHeight);
    s.set(kEnergy, std::abs(a.energy - b.energy), kLineMoves * (l.lift + l.share * share));
    if (l.shortest > 0) {  // plus the strain float positions resolve: u·R at each end
        const double strain = std::max(a.strain, b.strain);
        const double roundoff = 2 * kUnitRoundoff * radius / l.shortest;
        s.set(kStrain, std::abs(a.strain - b.strain),
              kLineMoves * (l.share * strain + l.friction) + roundoff + motion);
    }
    s.set(kContacts, double(std::abs(a.contacts - b.contacts)), kLineMoves * l.contacts);
    if (isSmoothChain(scene)) {
        const double extent = scene.grid().extent();
        s.set(kEnvelope, maxDifferenceOverExtent(gpu, cpu, extent),
              kEnvelopeFactor * std::sqrt(double(step + 1)) * kUnitRoundoff * radius / extent);
    }
    return s;
}

double largestRadius(const SimState& s) {
    double r = 0;
    for (const glm::dvec3& p : s.positions) r = std::max(r, glm::length(p));
    return r;
}

// Many steps per dispatch where the integrator has them: the same state bit for bit as the
// per-pass kernels (gpu_variants_test.cpp), on one core rather than llvmpipe's thread pool, which
// on cape and table (past Auto's 24² on software) takes a fifth less CPU time.
GpuOptions gpuOptionsFor(const Scene& scene) {
    GpuOptions options;
    const Method m = scene.integrator.method;
    if (m == Method::ExplicitEuler || m == Method::SymplecticEuler)
        options.dispatch = StepDispatch::ManySteps;
    return options;
}

// A scene the wind keeps moving: its cloth flutters for as long as the run lasts.
bool isWindDriven(const Scene& scene) {
    return scene.wind && scene.wind->strength > 0 && scene.grid().nu > 1 && scene.grid().nv > 1;
}

double valueOf(const Observables& x, Observable o) {
    switch (o) {
        case kMeanHeight:
            return x.meanHeight;
        case kEnergy:
            return x.energy;
        case kStrain:
            return x.strain;
        case kContacts:
            return double(x.contacts);
        default:
            return 0;
    }
}

// The time average of observable o over `series` past its first kMotionWindow samples (the fall
// from rest), and its standard error by batch means: batches of kMotionWindow samples (4 s, many
// flutter periods) are nearly independent, so the error is their spread over √batches.
std::pair<double, double> averageOf(const std::vector<Observables>& series, Observable o) {
    std::vector<double> batches;
    for (std::size_t b = kMotionWindow; b + kMotionWindow <= series.size(); b += kMotionWindow) {
        double sum = 0;
        for (std::size_t k = b; k < b + kMotionWindow; ++k) sum += valueOf(series[k], o);
        batches.push_back(sum / double(kMotionWindow));
    }
    double mean = 0, var = 0;
    for (double x : batches) mean += x / double(batches.size());
    for (double x : batches) var += (x - mean) * (x - mean) / double(batches.size() - 1);
    return {mean, std::sqrt(var / double(batches.size()))};
}

// A wind-driven scene's runs compared by their time averages: two flutters of the same flag
// agree in the mean up to the line moves (the largest bound of any sample) and kSigmas standard
// errors of the difference of the two averages.
Sample compareAverages(const std::vector<Observables>& gpu, const std::vector<Observables>& cpu,
                       const std::vector<Sample>& lineBounds, long steps) {
    Sample s;
    s.step = steps;
    s.averaged = true;
    for (Observable o : {kMeanHeight, kEnergy, kStrain, kContacts}) {
        double line = 0;
        for (const Sample& b : lineBounds) line = std::max(line, b.bound[o]);
        const auto [ma, ea] = averageOf(gpu, o);
        const auto [mb, eb] = averageOf(cpu, o);
        s.set(o, std::abs(ma - mb), line + kSigmas * std::sqrt(ea * ea + eb * eb));
    }
    return s;
}

// Runs `gpuScene` on the GPU (float) and `scene` on the CPU (double) for `steps`, each reading
// back only every kSampleEvery steps, and compares them by `scene`'s bounds.
Comparison compare(const Scene& gpuScene, const Scene& scene, long steps) {
    std::unique_ptr<Solver> gpu = makeGpuSolver(gpuScene, gpuOptionsFor(gpuScene));
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Double});
    Comparison c;
    double radius = largestRadius(cpu->read());     // R: max |p| of the double run so far [m]
    std::deque<Observables> recent;                 // the double run's last kMotionWindow samples
    std::vector<Observables> gpuSeries, cpuSeries;  // every sample of each run
    std::vector<Sample> lineBounds;  // the line moves' bounds alone, sample by sample
    const bool windDriven = isWindDriven(scene);
    using Clock = std::chrono::steady_clock;
    for (long done = 0; done < steps;) {
        const long chunk = std::min(kSampleEvery, steps - done);
        const auto t0 = Clock::now();
        const StepResult rg = gpu->step(chunk);
        const SimState sg = gpu->read();
        const auto t1 = Clock::now();
        const StepResult rc = cpu->step(chunk);
        const SimState sc = cpu->read();
        c.gpuSeconds += std::chrono::duration<double>(t1 - t0).count();
        c.cpuSeconds += std::chrono::duration<double>(Clock::now() - t1).count();
        done += chunk;
        if (rc.unstable) {
            c.stability.push_back("the double run itself is unstable: " + rc.reason);
            break;
        }
        if (rg.unstable) {
            c.stability.push_back("unstable at step " + std::to_string(rg.firstBadStep) + ": " +
                                  rg.reason);
            break;
        }
        if (const auto breach = strainBreach(gpuScene, sg); breach && !strainBreach(scene, sc))
            c.stability.push_back("step " + std::to_string(done) + ": " + *breach);
        radius = std::max(radius, largestRadius(sc));
        gpuSeries.push_back(observe(scene, sg, gpu->time()));
        cpuSeries.push_back(observe(scene, sc, cpu->time()));
        recent.push_back(cpuSeries.back());
        if (recent.size() > kMotionWindow) recent.pop_front();
        Sample s = compareAt(scene, gpuSeries.back(), cpuSeries.back(), strainMotion(recent), sg,
                             sc, done, radius);
        if (windDriven)
            lineBounds.push_back(
                compareAt(scene, gpuSeries.back(), cpuSeries.back(), 0, sg, sc, done, radius));
        if (windDriven)  // compared as time averages below, not state by state
            for (Observable o : {kMeanHeight, kEnergy, kStrain, kContacts}) s.ratio[o] = 0;
        c.samples.push_back(s);
    }
    if (windDriven && cpuSeries.size() >= 4 * kMotionWindow)  // the transient, then 3 batches
        c.samples.push_back(compareAverages(gpuSeries, cpuSeries, lineBounds, steps));
    for (const Sample& s : c.samples)
        for (int o = 0; o < kObservables; ++o) c.worst[o] = std::max(c.worst[o], s.ratio[o]);
    return c;
}

// One row of the table: the worst observed/bound per observable over the run.
void printRow(const std::string& scene, long steps, const Comparison& c, bool envelope) {
    static bool header = false;
    if (!header) {
        std::printf("%-12s %7s %6s %6s | worst |difference| / bound: %11s %7s %7s %8s %8s\n",
                    "scene", "steps", "gpu s", "cpu s", "mean height", "energy", "strain",
                    "contacts", "envelope");
        header = true;
    }
    std::printf("%-12s %7ld %6.1f %6.1f | %39.3f %7.3f %7.3f %8.3f", scene.c_str(), steps,
                c.gpuSeconds, c.cpuSeconds, c.worst[kMeanHeight], c.worst[kEnergy],
                c.worst[kStrain], c.worst[kContacts]);
    if (envelope)
        std::printf(" %8.3f\n", c.worst[kEnvelope]);
    else
        std::printf(" %8s\n", "-");
}

// The first sample past each bound, as a failure message; empty when every sample is within.
std::vector<std::string> exceedances(const Comparison& c) {
    std::vector<std::string> out;
    for (int o = 0; o < kObservables; ++o)
        for (const Sample& s : c.samples)
            if (!(s.ratio[o] <= 1)) {  // NaN counts as past
                char buf[200];
                std::snprintf(buf, sizeof buf, "%s%s differs by %.3g at step %ld, bound %.3g",
                              s.averaged ? "time-averaged " : "", kNames[o], s.observed[o], s.step,
                              s.bound[o]);
                out.push_back(buf);
                break;
            }
    return out;
}

class GpuLongDivergence : public GpuTest, public ::testing::WithParamInterface<std::string> {};
using GpuLongDivergenceTeeth = GpuTest;

TEST_P(GpuLongDivergence, ObservablesStayWithinTheirBoundsOverALongRun) {
    const Scene scene = withoutSelfCollision(loadShippedScene(GetParam()));
    const long steps = stepsFor(GetParam());
    const Comparison c = compare(scene, scene, steps);
    printRow(GetParam(), steps, c, isSmoothChain(scene));
    for (const std::string& s : c.stability) ADD_FAILURE() << GetParam() << ", float run: " << s;
    const long states = long(std::count_if(c.samples.begin(), c.samples.end(),
                                           [](const Sample& s) { return !s.averaged; }));
    EXPECT_EQ(states, steps / kSampleEvery) << "the run stopped early";
    for (const std::string& e : exceedances(c)) ADD_FAILURE() << GetParam() << ": " << e;
}

INSTANTIATE_TEST_SUITE_P(ShippedScenes, GpuLongDivergence, ::testing::ValuesIn(shippedSceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& p) {
                             std::string name = p.param;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

// The bounds have teeth: a GPU run given 10 % more damping than the double run (a kernel with a
// wrong damping term) falls measurably slower, and a flag given 30 % less wind flutters lower.
// Measured (worst difference / bound): the chain leaves the per-vertex envelope within the first
// 1000 steps (860); the hanging cloth, with its drag raised to 20 s⁻¹ in both runs (the seed's
// per-vertex scene's μ/m, a fall the drag paces: denim's own 0.46 s⁻¹ barely slows a fall of
// half a second), leaves the mean height's bound (1.45); the flag's time-averaged mean height
// leaves its bound (1.34; 10 % less wind stays inside, 0.46).
TEST_F(GpuLongDivergenceTeeth, MoreDampingOrLessWindOnTheGpuLeavesTheBounds) {
    struct Case {
        const char* name;
        long steps;
        Observable observable;
        std::vector<std::string> sets;  // applied to both runs
        void (*defect)(Scene&);         // applied to the GPU's
    };
    const Case cases[] = {
        {"chain", 20000, kEnvelope, {}, [](Scene& s) { s.damping *= 1.1; }},
        {"hanging",
         50000,
         kMeanHeight,
         {"material.air_damping=20"},
         [](Scene& s) { s.material->airDamping *= 1.1; }},
        {"flag", 100000, kMeanHeight, {}, [](Scene& s) { s.wind->strength *= 0.7; }},
    };
    for (const Case& k : cases) {
        const Scene scene =
            loadScene(std::string(CLOTH_SOURCE_DIR) + "/scenes/" + k.name + ".json", k.sets);
        Scene broken = scene;
        k.defect(broken);
        const Comparison c = compare(broken, scene, k.steps);
        printRow(std::string(k.name) + " defect", k.steps, c, isSmoothChain(scene));
        EXPECT_GT(c.worst[k.observable], 1) << k.name << ": " << kNames[k.observable];
        EXPECT_FALSE(exceedances(c).empty()) << k.name;
    }
}

}  // namespace
}  // namespace cloth::test
