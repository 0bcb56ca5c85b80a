// The CPU backend on a cloth of a material (tests/support/material_scene.h): vertex masses lumped
// from the area, structural springs of different K along u and v, the drag −c·m_k·v_k. Against
// the reference (which lumps the masses itself from the density) to integrator_parity_test.cpp's
// tolerances; the masses the solver models, measured; a free fall against the drag law; the
// stability bound of the lightest vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "cpu/cpu_backend.h"
#include "model/stability.h"
#include "reference/reference.h"
#include "solver/diagnostics.h"
#include "support/material_scene.h"
#include "support/reference_bridge.h"

namespace cloth {
namespace {

constexpr long kSteps = 1000;
constexpr double kDoubleTolerance = 1e-12;   // max |p − p_ref| / extent
constexpr double kImplicitTolerance = 1e-9;  // both CGs stopped at |r| ≤ 1e-12 |b|
constexpr double kFloatTolerance = 1e-5;

// Explicit Euler has no stable Δt on this cloth (its stiffest mode needs Δt < c/ω² ≈ 1e-9 s):
// it runs 200 steps of 1e-5 s, over which that mode grows by 1.1% a step.
Scene sceneFor(Method method) {
    Scene s = materialScene(method, method == Method::ExplicitEuler ? 1e-5 : 1e-4);
    s.integrator.tolerance = 1e-12;
    s.integrator.maxIterations = 1000;
    return s;
}
long stepsFor(Method method) {
    return method == Method::ExplicitEuler ? 200 : kSteps;
}

SimState runCpu(const Scene& scene, Precision precision, int threads, long steps) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {precision, threads});
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << methodName(scene.integrator.method) << ": " << r.reason;
    EXPECT_EQ(r.stepsTaken, steps);
    EXPECT_EQ(solver->solveStats().misses, 0) << methodName(scene.integrator.method);
    return solver->read();
}

ref::Simulation runReference(const ref::Params& params, long steps) {
    ref::Simulation sim(params);
    for (long n = 0; n < steps; ++n) sim.step();
    EXPECT_TRUE(sim.finiteAndBelowMaxSpeed());
    return sim;
}

// Largest distance of two runs' positions, over the extent.
double maxDeviation(const ref::Simulation& a, const ref::Simulation& b, double extent) {
    double worst = 0;
    for (std::size_t k = 0; k < a.positions().size(); ++k) {
        double d2 = 0;
        for (int c = 0; c < 3; ++c) d2 += std::pow(a.positions()[k][c] - b.positions()[k][c], 2);
        worst = std::max(worst, std::sqrt(d2));
    }
    return worst / extent;
}

TEST(Material, CpuMatchesTheReferenceForEveryMethod) {
    for (Method method : kMethods) {
        // vbd's 10 iterations do not converge to its reference, backward Euler: its parity is
        // tests/cpu/vbd_test.cpp's, at convergence.
        if (method == Method::Vbd) continue;
        const Scene scene = sceneFor(method);
        const long steps = stepsFor(method);
        const double extent = scene.grid().extent();
        const ref::Params params = toReference(scene);
        const ref::Simulation expected = runReference(params, steps);
        // Not vacuous: the same cloth with its mass spread evenly ends far from it.
        ref::Params even = params;
        even.density = 0;
        even.mass = scene.totalMass() / double(scene.grid().count());
        const double lumping = maxDeviation(runReference(even, steps), expected, extent);
        const double tolerance =
            method == Method::ImplicitEuler ? kImplicitTolerance : kDoubleTolerance;
        EXPECT_GT(lumping, 100 * tolerance) << methodName(method);
        if (method != Method::ExplicitEuler) {  // its 2 ms are too short for float to tell
            EXPECT_GT(lumping, 100 * kFloatTolerance) << methodName(method);
        }
        for (int threads : {1, 2}) {
            const double dev = maxDeviationOverExtent(
                runCpu(scene, Precision::Double, threads, steps), expected, extent);
            EXPECT_LT(dev, tolerance) << methodName(method) << ", " << threads << " threads";
            std::printf("%-16s double, %d thread(s): max |p - p_ref| / extent = %.3g\n",
                        methodName(method), threads, dev);
        }
        const double devF =
            maxDeviationOverExtent(runCpu(scene, Precision::Float, 1, steps), expected, extent);
        EXPECT_LT(devF, kFloatTolerance) << methodName(method) << ", float";
        std::printf("%-16s float: %.3g; evenly spread mass: %.3g\n", methodName(method), devF,
                    lumping);
    }
}

// The masses the solver models, read off one step of a wind of known force: each vertex's is
// its share of the area times the density (corners ¼, edges ½ of a cell's), they sum to
// density × area, and their centre is the sheet's centroid. After setParameters with twice the
// density, each is twice as heavy; a vertex pinned and released has its own mass again. Each
// change is made to the state at rest and read off the next step (a write() would set the
// masses afresh).
TEST(Material, SolverMassesAreTheLumpedAreaTimesTheDensity) {
    for (Precision precision : {Precision::Double, Precision::Float}) {
        Scene probe = massProbeScene(materialScene(Method::SymplecticEuler));
        // Float: the rest lengths' rounding (1e-7 of the wind) and the wind's own.
        const double tolerance = precision == Precision::Double ? 1e-12 : 1e-5;
        const std::string name = precisionName(precision);
        std::unique_ptr<Solver> solver = makeCpuSolver(probe, {precision, 1});
        const SimState rest = solver->read();
        const double density = probe.material->density;
        expectLumpedMasses(probe, density, stepMasses(*solver, probe), tolerance, name);
        solver->write(rest);
        probe.material->density = 2 * density;
        solver->setParameters(probe);
        expectLumpedMasses(probe, 2 * density, stepMasses(*solver, probe), tolerance,
                           name + ", density doubled");
        solver->write(rest);
        solver->setPinned(0, 0, true);
        solver->setPinned(0, 0, false);
        expectLumpedMasses(probe, 2 * density, stepMasses(*solver, probe), tolerance,
                           name + ", corner pinned and released");
        EXPECT_DOUBLE_EQ(probe.totalMass(), 2 * density * probe.cloth.size.x * probe.cloth.size.y);
    }
}

// A material's wind is a pressure (docs/physics.md "Wind"): the sheet takes the impulse
// Δt·P·area·cos θ at every resolution, and every vertex the same acceleration, its force
// scaling with its share of the area as its mass does. (A force per vertex, the per-vertex
// form's, gives N/area m⁻² times it: 84 at 8 cells, 1100 at 32, seen with windArea 1.) Float:
// the rounding of the wind's force and of the rest lengths, 5e-8 seen.
TEST(Material, WindIsAPressureAtEveryResolution) {
    for (Precision precision : {Precision::Double, Precision::Float})
        for (int cells : {8, 32, 128}) {
            const Scene scene = windSheetScene(cells);
            std::unique_ptr<Solver> solver = makeCpuSolver(scene, {precision, 2});
            solver->step(1);
            const WindImpulse w = windImpulse(scene, solver->read());
            std::printf("%s, %3d cells: impulse / (dt P A cos) = %.9f, speeds spread %.2g\n",
                        precisionName(precision), cells, w.ofPressure, w.spread);
            const double tolerance = precision == Precision::Double ? 1e-9 : 1e-4;
            EXPECT_NEAR(w.ofPressure, 1, tolerance) << cells << " cells";
            EXPECT_LT(w.spread, tolerance) << cells << " cells";
        }
}

// Every vertex has the same drag rate c, so an unpinned sheet falls without deforming and its
// centre of mass follows v(t) = g/c (1 − e^{−ct}); its kinetic energy is ½ ρA|v|². Δt = 1e-4 s
// over t = 0.5 s with c = 4/s: the first-order schemes miss the law by ½ g c h t e^{−ct}
// (1.3e-4 m/s of 2.1 m/s), Verlet and RK4 by far less. In float the rounding of the positions
// (1e-7 m) stretches the stiff springs a little every step: the sheet ripples at that amplitude
// (strain 2e-5 seen), its light corners fastest, and the centre of mass's speed carries float's
// rounding of 5000 additions (a random walk of √5000 · 1.2e-7 ≈ 1e-5 m/s; 1e-7 seen).
TEST(Material, FreeFallFollowsTheDragLaw) {
    const double c = 4, t = 0.5, h = 1e-4, g = 9.81;
    const long steps = std::lround(t / h);
    const double law = g / c * (1 - std::exp(-c * t));
    const double firstOrder = 0.5 * g * c * h * t * std::exp(-c * t);
    for (Method method : kMethods) {
        if (method == Method::ExplicitEuler) continue;  // no stable Δt (see sceneFor)
        // vbd's velocity is a difference of positions over h: at Δt = 1e-4 in float it carries
        // their rounding / h. Its drag law is tests/cpu/vbd_test.cpp's, at Δt = 1/60.
        if (method == Method::Vbd) continue;
        Scene scene = fallingMaterialScene(method, c, h);
        scene.integrator.tolerance = 1e-12;  // implicit Euler: an exact solve keeps it rigid
        for (Precision precision : {Precision::Double, Precision::Float}) {
            const bool exact = precision == Precision::Double;
            std::unique_ptr<Solver> solver = makeCpuSolver(scene, {precision, 1});
            const StepResult r = solver->step(steps);
            ASSERT_FALSE(r.unstable) << methodName(method) << ": " << r.reason;
            const SimState s = solver->read();
            const FallingSheet f = fallingSheet(scene, s);
            std::printf(
                "%-16s %s: v = %.9g m/s, drag law %.9g, spread %.3g m/s, |v_xz| %.3g m/s, strain "
                "%.3g\n",
                methodName(method), precisionName(precision), -f.velocity.y, law, f.spread,
                f.sideways, f.strain);
            const std::string what =
                std::string(methodName(method)) + " " + precisionName(precision);
            EXPECT_NEAR(-f.velocity.y, law, 2 * firstOrder + (exact ? 0 : 1e-4 * law)) << what;
            EXPECT_LT(f.sideways, (exact ? 1e-12 : 1e-5) * law) << what;
            EXPECT_LT(f.strain, exact ? 1e-12 : 1e-4) << what;
            if (exact) {
                EXPECT_LT(f.spread, 1e-9 * law) << what;
                const double kinetic = 0.5 * scene.totalMass() * glm::dot(f.velocity, f.velocity);
                EXPECT_NEAR(energy(scene, s).kinetic, kinetic, 1e-9 * kinetic) << what;
            }
        }
    }
}

// The predicted bound comes from the lightest vertices (the corners, λ_k/m_k four times an
// interior one's stiffness per mass): inside it the hanging sheet stays bounded, past it it runs
// away within a few hundred steps.
TEST(Material, StableInsideThePredictedBoundUnstableBeyond) {
    Scene scene = materialScene(Method::SymplecticEuler);
    const StabilityBound b = estimateStability(scene, 40);
    const double tight = b.tightDt(Method::SymplecticEuler);
    EXPECT_LE(b.safeDt(Method::SymplecticEuler), tight);
    EXPECT_LE(b.omega2Power, b.omega2Max);
    for (double factor : {0.8, 1.25}) {
        scene.integrator.dt = factor * tight;
        const StepResult r = makeCpuSolver(scene, {Precision::Double, 1})->step(2000);
        EXPECT_EQ(r.unstable, factor > 1)
            << "dt = " << factor << " x " << tight << ": " << r.reason;
    }
}

}  // namespace
}  // namespace cloth
