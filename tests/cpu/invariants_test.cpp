// Invariants of the model of DESIGN.md §2 kept by the CPU backend (DESIGN.md §6): pins fixed,
// mirror symmetry kept, nothing inside a collider, energy decaying with damping and no wind,
// and wind pushing the cloth along the wind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <variant>

#include "cpu/cpu_backend.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

// A cloth hanging in the xy plane from its two top corners, 9 × 13 vertices 0.125 m apart
// (dyadic, so every rest position and its mirror image about x = 0 are exact in float and
// double), all three spring families, damping inside the explicit Euler bound
// Δt < μ/λ_max, λ_max ≤ 2·4·(300 + 100 + 30) = 3440 N/m → μ/λ_max ≈ 5.8e-4 s > 5e-4 s.
constexpr const char* kHangingScene = R"({
  "cloth": { "resolution": [9, 13], "size": [1.0, 1.5], "origin": [-0.5, 1.0, 0.0],
             "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": 0.5 },
  "springs": { "structural": 300.0, "shear": 100.0, "bend": 30.0 },
  "damping": 2.0,
  "pins": [[0, 0], [-1, 0]],
  "integrator": { "method": "explicit_euler", "dt": 0.0005 }
})";

// The same cloth blown out of its plane by a wind along +z (mirror-symmetric about x = 0) onto a
// sphere centred on the mirror plane.
const std::vector<std::string> kWindAndSphere = {
    R"(wind={"direction": [0, 0, 1], "strength": 3.0})",
    R"(colliders=[{"type": "sphere", "center": [0, 0.2, 0.5], "radius": 0.3}])"};

Scene hangingScene(const std::vector<std::string>& overrides = {}) {
    return parseScene(kHangingScene, "hanging (test)", overrides);
}

// A cloth falling flat onto a sphere that rests above a floor, the two colliders apart so that
// no push out of one can push into the other. Δt = 5e-4 s < μ/λ_max = 1.5/(2·4·260) ≈ 7.2e-4 s.
constexpr const char* kDrapeScene = R"({
  "cloth": { "resolution": [24, 19], "size": [1.6, 1.4], "origin": [-0.8, 0.9, -0.7],
             "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.1 },
  "springs": { "structural": 200.0, "shear": 50.0, "bend": 10.0 },
  "damping": 1.5,
  "integrator": { "method": "explicit_euler", "dt": 0.0005 },
  "colliders": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] },
                 { "type": "sphere", "center": [0.1, 0.45, 0], "radius": 0.3 } ]
})";

std::unique_ptr<Solver> cpuSolver(const Scene& scene, Precision precision) {
    return makeCpuSolver(scene, {precision, 1});
}

const char* label(Precision p) {
    return precisionName(p);
}

// §2: pinned vertices are reset to their pinned position every step: bitwise, not approximately.
TEST(Invariants, PinsStayExactlyFixed) {
    const Scene scene = hangingScene(kWindAndSphere);
    for (Precision precision : {Precision::Double, Precision::Float}) {
        std::unique_ptr<Solver> solver = cpuSolver(scene, precision);
        const SimState start = solver->read();
        for (int chunk = 0; chunk < 20; ++chunk) {
            ASSERT_FALSE(solver->step(50).unstable);
            const SimState s = solver->read();
            for (const Pin& pin : scene.pins) {
                const std::size_t k = std::size_t(scene.grid().index(pin.i, pin.j));
                EXPECT_EQ(0, std::memcmp(&s.positions[k], &start.positions[k], sizeof(glm::dvec3)))
                    << label(precision) << ", pin (" << pin.i << ", " << pin.j << ")";
                EXPECT_EQ(s.velocities[k], glm::dvec3(0)) << label(precision);
            }
        }
        // Something else did move, so the check above is not vacuous.
        EXPECT_GT(glm::length(solver->read().positions.back() - start.positions.back()), 0.01);
    }
}

// Largest |p_k − M p_k'| over mirror pairs k = (i, j), k' = (nu−1−i, j), M: x → −x, relative to
// the extent.
double mirrorAsymmetry(const SimState& s, double extent) {
    double worst = 0;
    for (int j = 0; j < s.nv; ++j) {
        for (int i = 0; i < s.nu; ++i) {
            const glm::dvec3 p = s.positions[std::size_t(j) * s.nu + i];
            glm::dvec3 q = s.positions[std::size_t(j) * s.nu + (s.nu - 1 - i)];
            q.x = -q.x;
            worst = std::max(worst, glm::length(p - q));
        }
    }
    return worst / extent;
}

// A mirror-symmetric scene stays mirror-symmetric. The initial state is mirror-exact (dyadic
// grid) and each spring, normal and collider term of a vertex is the exact mirror image of its
// partner's (IEEE negation is exact). The only asymmetry is the order in which a vertex sums its
// 12 neighbour forces: (+1, 0) before (−1, 0) for both partners, so their sums round
// differently by an ulp or so. A stable damped run does not amplify that: 1e-12 in double leaves
// four orders of magnitude for accumulated rounding; float gets the same margin over its ulp.
TEST(Invariants, MirrorSymmetricClothStaysSymmetric) {
    for (const bool windAndSphere : {false, true}) {
        const Scene scene = windAndSphere ? hangingScene(kWindAndSphere) : hangingScene();
        for (Precision precision : {Precision::Double, Precision::Float}) {
            const double tolerance = precision == Precision::Double ? 1e-12 : 1e-5;
            std::unique_ptr<Solver> solver = cpuSolver(scene, precision);
            double worst = 0;
            for (int chunk = 0; chunk < 30; ++chunk) {
                ASSERT_FALSE(solver->step(100).unstable);
                worst = std::max(worst, mirrorAsymmetry(solver->read(), scene.grid().extent()));
            }
            std::printf("mirror asymmetry (%s, %s): %.3g\n", label(precision),
                        windAndSphere ? "wind + sphere" : "in-plane", worst);
            EXPECT_LT(worst, tolerance) << label(precision) << (windAndSphere ? " wind" : "");
            if (windAndSphere) {  // the wind really took it out of its plane
                EXPECT_GT(solver->read().positions.back().z, 0.1);
            }
        }
    }
}

// Signed distance outside each collider, the most negative over all vertices, relative to the
// extent: §2's plane and sphere rules leave every vertex on or outside the surface.
double deepestPenetration(const Scene& scene, const SimState& s) {
    double deepest = 0;
    for (const glm::dvec3& p : s.positions) {
        for (const Collider& c : scene.colliders) {
            double outside = 0;
            if (const Plane* plane = c.as<Plane>())
                outside = glm::dot(p - plane->point, plane->normal);
            else if (const Sphere* sphere = c.as<Sphere>())
                outside = glm::length(p - sphere->center) - sphere->radius;
            deepest = std::min(deepest, outside);
        }
    }
    return -deepest / scene.grid().extent();
}

TEST(Invariants, NoVertexEndsAStepInsideACollider) {
    const Scene scene = parseScene(kDrapeScene, "drape (test)");
    for (Precision precision : {Precision::Double, Precision::Float}) {
        // Rounding of the projection itself: a few ulp of the coordinates (≈ 1 m).
        const double tolerance = precision == Precision::Double ? 1e-14 : 1e-6;
        std::unique_ptr<Solver> solver = cpuSolver(scene, precision);
        double deepest = 0;
        for (int step = 0; step < 4000; ++step) {
            ASSERT_FALSE(solver->step(1).unstable);
            deepest = std::max(deepest, deepestPenetration(scene, solver->read()));
        }
        std::printf("deepest penetration (%s): %.3g of the extent\n", label(precision), deepest);
        EXPECT_LT(deepest, tolerance) << label(precision);
        // The cloth did reach both: its corners lie on the floor, its middle on the sphere.
        const SimState s = solver->read();
        EXPECT_LT(s.positions.front().y, 1e-3) << label(precision);  // (0, 0) on the floor
        EXPECT_NEAR(glm::length(s.positions[std::size_t(9 * 24 + 13)] - glm::dvec3(0.1, 0.45, 0)),
                    0.3, 0.02)
            << label(precision);
    }
}

// Total energy (kinetic + spring + gravity) with damping and no wind (DESIGN.md §6). The exact
// dynamics dissipate 2(μ/m)·KE per second; explicit Euler adds O(Δt²) per step, so single steps
// can gain energy (at a turning point, v ≈ 0, the gain ≈ ½ m ω⁴ Δt² x² has nothing to offset it).
// Per mode of frequency ω its energy oscillates within a period by a fraction ≈ ωΔt about an
// envelope that decays by c Δt (1 − λΔt/μ) per step, c = μ/m, which is positive inside the bound
// Δt < μ/λ_max. A window of W ≥ ω_max / (c (1 − λ_max Δt/μ)) steps is therefore long enough for
// the envelope to dominate; we take 8× that and check energy(end) ≤ energy(start) per window.
TEST(Invariants, DampedEnergyDecaysWithoutWind) {
    const Scene scene = hangingScene({"integrator.dt=0.00025"});
    ASSERT_FALSE(scene.wind.has_value());
    const double m = scene.cloth.mass, mu = scene.damping, dt = scene.integrator.dt;
    const double k = scene.springs.structural + scene.springs.shear + scene.springs.bend;
    const double lambdaMax = 2 * 4 * k;  // Gershgorin: twice the stiffness meeting at a vertex
    ASSERT_LT(lambdaMax * dt / mu, 1.0) << "the scene must lie inside the stability bound";
    const double c = mu / m, omegaMax = std::sqrt(lambdaMax / m);
    const long window = std::lround(std::ceil(8 * omegaMax / (c * (1 - lambdaMax * dt / mu))));
    const ref::Simulation model(toReference(scene));
    for (Precision precision : {Precision::Double, Precision::Float}) {
        std::unique_ptr<Solver> solver = cpuSolver(scene, precision);
        const double e0 = totalEnergy(model, solver->read());
        double start = e0;
        int windows = 0;
        for (; solver->stepsDone() + window <= 6000; ++windows) {
            ASSERT_FALSE(solver->step(window).unstable);
            const SimState s = solver->read();
            const double end = totalEnergy(model, s);
            // Summation rounding of a sum whose terms reach |E_gravity|.
            const double noise = (precision == Precision::Double ? 1e-12 : 1e-5) *
                                 std::abs(model.gravityEnergy(toReferenceVectors(s.positions)));
            EXPECT_LE(end, start + noise)
                << label(precision) << ", window " << windows << " of " << window << " steps";
            start = end;
        }
        std::printf("energy (%s): %.6g J -> %.6g J over %d windows of %ld steps\n",
                    label(precision), e0, start, windows, window);
        EXPECT_LT(start, e0 - 1.0) << label(precision);  // it fell and lost energy to damping
    }
}

// Mean displacement of the vertices along `direction` since the start [m].
double meanDisplacementAlong(const SimState& start, const SimState& end, glm::dvec3 direction) {
    double sum = 0;
    for (std::size_t k = 0; k < end.positions.size(); ++k)
        sum += glm::dot(end.positions[k] - start.positions[k], direction);
    return sum / double(end.positions.size());
}

// Wind (seed §5.3): F_w = K_w ⟨n, û_w⟩ n, so ⟨F_w, û_w⟩ = K_w ⟨n, û_w⟩² ≥ 0: a flag pinned
// along its edge is pushed along the wind. Without wind it only sags in its own plane, which
// moves it slightly against this wind (whose x component points away from the pinned edge).
TEST(Invariants, WindPushesAFlagAlongTheWind) {
    std::string pins = "pins=[";
    for (int j = 0; j < 13; ++j) pins += (j ? ", [0, " : "[0, ") + std::to_string(j) + "]";
    pins += "]";
    const glm::dvec3 direction = glm::normalize(glm::dvec3(0.3, 0, 1));
    const std::string wind = R"(wind={"direction": [0.3, 0, 1], "strength": 3.0})";
    for (Precision precision : {Precision::Double, Precision::Float}) {
        double displacement[2];
        for (int withWind = 0; withWind < 2; ++withWind) {
            const Scene scene = withWind ? hangingScene({pins, wind}) : hangingScene({pins});
            std::unique_ptr<Solver> solver = cpuSolver(scene, precision);
            const SimState start = solver->read();
            ASSERT_FALSE(solver->step(2000).unstable);
            displacement[withWind] = meanDisplacementAlong(start, solver->read(), direction);
        }
        std::printf("mean displacement along the wind (%s): %.4g m with, %.4g m without\n",
                    label(precision), displacement[1], displacement[0]);
        EXPECT_GT(displacement[1], 0.05) << label(precision);
        EXPECT_GT(displacement[1] - displacement[0], 0.1) << label(precision);  // extent 1.8 m
    }
}

}  // namespace
}  // namespace cloth
