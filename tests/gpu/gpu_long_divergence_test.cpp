// Long runs, float GPU against double CPU (docs/gpu.md "Error bound for long runs"): every
// shipped scene for 100 000 steps on both, compared every 1000 steps by what a user compares.
//
// Once contact, folds or flapping amplify rounding, two correct runs put a fold or a contact edge
// in different cells and their per-vertex positions separate. Each run resolves such a line to one
// cell h = max(du, dv) of the continuum cloth's, so two runs differ by at most two "line moves":
// a line of P vertices (P = the grid's border vertices, the longest line a convex fold or contact
// edge can form on the cloth) moved by h. The bounds are twice an observable's change under one
// line move; with N vertices of mass m, g = |g|, K the structural stiffness, L its shorter rest
// length and μ_f the largest friction coefficient of the colliders:
//   mean height     |Δȳ| ≤ 2 P h / N                   (P vertices lifted by h)
//   energy          |ΔE| ≤ 2 (m g P h + (P/N)(K + S))  (their weight lifted by h, and their
//                                                      share of kinetic and spring energy)
//   largest strain  |Δε| ≤ 2 ((P/N) ε + μ_f P m g/(K L))
//                                                      (their share of the load on the most
//                                                      strained spring, and the tension their
//                                                      friction can lock in)
//   contact count   |ΔC| ≤ 2 P                         (each of them touching in one run)
// K + S and ε are the larger of the two runs', and the strain bound adds 2·u·R/L, the strain
// float positions resolve (u = 2^-24, R = max |p|). A chain (one row of vertices) with neither
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
constexpr long kSampleEvery = 1000;
constexpr double kLineMoves = 2;                   // one per run, see above
constexpr double kUnitRoundoff = FLT_EPSILON / 2;  // u = 2^-24
constexpr double kEnvelopeFactor = 4;              // gpu_divergence_test.cpp, docs/gpu.md
// A vertex touches a collider when it lies within this fraction of a cell of the collider's
// offset surface: 5·10⁻⁶ m on the shipped scenes, 40 times the float rounding of a position
// (u·2 m), far below anything the grid resolves.
constexpr double kContactBand = 1e-4;

// The shipped scenes, by file name without ".json", sorted: a scene added later is compared too.
std::vector<std::string> shippedSceneNames() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(CLOTH_SOURCE_DIR "/scenes"))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
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
    const double weight = scene.cloth.mass * glm::length(scene.gravity);  // m g [N]
    double mu = 0;                                                        // μ_f
    for (const Collider& c : scene.colliders) mu = std::max(mu, c.friction);
    const double stiffness = scene.springs.structural;
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

Sample compareAt(const Scene& scene, const SimState& gpu, const SimState& cpu, long step, double t,
                 double radius) {
    const LineMove l = lineMoveOf(scene);
    const Observables a = observe(scene, gpu, t), b = observe(scene, cpu, t);
    const double share = std::max(a.kineticAndSpring, b.kineticAndSpring);
    Sample s;
    s.step = step;
    s.set(kMeanHeight, std::abs(a.meanHeight - b.meanHeight), kLineMoves * l.meanHeight);
    s.set(kEnergy, std::abs(a.energy - b.energy), kLineMoves * (l.lift + l.share * share));
    if (l.shortest > 0) {  // plus the strain float positions resolve: u·R at each end
        const double strain = std::max(a.strain, b.strain);
        const double roundoff = 2 * kUnitRoundoff * radius / l.shortest;
        s.set(kStrain, std::abs(a.strain - b.strain),
              kLineMoves * (l.share * strain + l.friction) + roundoff);
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

// Runs `gpuScene` on the GPU (float) and `scene` on the CPU (double) for `steps`, each reading
// back only every kSampleEvery steps, and compares them by `scene`'s bounds.
Comparison compare(const Scene& gpuScene, const Scene& scene, long steps) {
    std::unique_ptr<Solver> gpu = makeGpuSolver(gpuScene, gpuOptionsFor(gpuScene));
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Double});
    Comparison c;
    double radius = largestRadius(cpu->read());  // R: max |p| of the double run so far [m]
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
        c.samples.push_back(compareAt(scene, sg, sc, done, gpu->time(), radius));
        for (int o = 0; o < kObservables; ++o)
            c.worst[o] = std::max(c.worst[o], c.samples.back().ratio[o]);
    }
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
                std::snprintf(buf, sizeof buf, "%s differs by %.3g at step %ld, bound %.3g",
                              kNames[o], s.observed[o], s.step, s.bound[o]);
                out.push_back(buf);
                break;
            }
    return out;
}

class GpuLongDivergence : public GpuTest, public ::testing::WithParamInterface<std::string> {};
using GpuLongDivergenceTeeth = GpuTest;

TEST_P(GpuLongDivergence, ObservablesStayWithinTheirBoundsFor100000Steps) {
    const Scene scene = loadShippedScene(GetParam());
    const Comparison c = compare(scene, scene, kSteps);
    printRow(GetParam(), kSteps, c, isSmoothChain(scene));
    for (const std::string& s : c.stability) ADD_FAILURE() << GetParam() << ", float run: " << s;
    EXPECT_EQ(long(c.samples.size()), kSteps / kSampleEvery) << "the run stopped early";
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
// wrong damping term) falls measurably slower. The hanging cloth's mean height leaves its bound
// after ~25 000 steps (1.5 times it at 50 000, the gap growing with the fall); the chain leaves
// the per-vertex envelope within the first 1000 steps.
TEST_F(GpuLongDivergenceTeeth, TenPercentMoreDampingOnTheGpuLeavesTheBounds) {
    for (const auto& [name, steps, observable] :
         {std::tuple{"hanging", 50000L, kMeanHeight}, std::tuple{"chain", 20000L, kEnvelope}}) {
        const Scene scene = loadShippedScene(name);
        Scene broken = scene;
        broken.damping *= 1.1;
        const Comparison c = compare(broken, scene, steps);
        printRow(std::string(name) + "+10%", steps, c, isSmoothChain(scene));
        EXPECT_GT(c.worst[observable], 1) << name << ": " << kNames[observable];
        EXPECT_FALSE(exceedances(c).empty()) << name;
    }
}

}  // namespace
}  // namespace cloth::test
