// The observables a long run is compared by, float GPU against double CPU, and their bounds
// (gpu_long_divergence_test.cpp).
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
// A chain (one row of vertices) with neither colliders nor wind has nothing to fold, buckle or
// touch: there the per-vertex envelope E(n) = 4·√(n + 1)·u·R/extent of the smooth regime
// (gpu_divergence_test.cpp) holds for the whole run as well. And wherever the double run is stable
// the float run must be: no instability report, no spring beyond max_strain.
#pragma once

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <deque>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "gpu/gpu_test_support.h"
#include "model/collider_pose.h"
#include "solver/diagnostics.h"

namespace cloth::test {

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

struct Observables {
    double energy = 0;            // kinetic + gravity + spring [J] (solver/diagnostics.h)
    double kineticAndSpring = 0;  // K + S [J]
    double meanHeight = 0;        // mean of ⟨p, −ĝ⟩, the centre of mass's height [m]
    double strain = 0;            // maxStrain: the largest structural stretch
    long contacts = 0;            // vertices within the contact band of a collider
};

// Up: −ĝ, or y where there is no gravity.
inline glm::dvec3 upOf(const Scene& scene) {
    const double g = glm::length(scene.gravity);
    return g > 0 ? -scene.gravity / g : glm::dvec3(0, 1, 0);
}

inline long contactCount(const Scene& scene, const SimState& s, double t) {
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

inline Observables observe(const Scene& scene, const SimState& s, double t) {
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

inline LineMove lineMoveOf(const Scene& scene) {
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
inline bool isSmoothChain(const Scene& scene) {
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

// How far the double run's largest strain has ranged (max − min) over its last kMotionWindow
// samples, `recent`: the motion of a cloth still swinging.
inline double strainMotion(const std::deque<Observables>& recent) {
    double lo = recent.front().strain, hi = lo;
    for (const Observables& o : recent) {
        lo = std::min(lo, o.strain);
        hi = std::max(hi, o.strain);
    }
    return hi - lo;
}

// `a` and `b` are the float and double runs' observables at this sample, `motion` the double
// run's strainMotion (0: the line moves alone).
inline Sample compareAt(const Scene& scene, const Observables& a, const Observables& b,
                        double motion, const SimState& gpu, const SimState& cpu, long step,
                        double radius) {
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

inline double largestRadius(const SimState& s) {
    double r = 0;
    for (const glm::dvec3& p : s.positions) r = std::max(r, glm::length(p));
    return r;
}

// A scene the wind keeps moving: its cloth flutters for as long as the run lasts.
inline bool isWindDriven(const Scene& scene) {
    return scene.wind && scene.wind->strength > 0 && scene.grid().nu > 1 && scene.grid().nv > 1;
}

inline double valueOf(const Observables& x, Observable o) {
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
inline std::pair<double, double> averageOf(const std::vector<Observables>& series, Observable o) {
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
inline Sample compareAverages(const std::vector<Observables>& gpu,
                              const std::vector<Observables>& cpu,
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

}  // namespace cloth::test
