// A material's spring damping (docs/physics.md "Spring damping"): each spring adds
// β K ((v_q − v_k)·d̂) d̂. A single damped spring against the closed form of a damped oscillator;
// rigid motion is not damped; the row kernels give the vertex-by-vertex path's bits for every
// instruction set and thread count; the CPU backend matches the reference, which writes the
// force as a scatter over springs; implicit Euler's system carries the damping Jacobian; the
// energy is dissipated; the stability bound follows c + βω².
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>

#include "cpu/cpu_backend.h"
#include "cpu/cpu_solver.h"
#include "model/stability.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "support/material_scene.h"
#include "support/reference_bridge.h"
#include "support/same_bits.h"
#include "support/sanitized.h"

namespace cloth {
namespace {

using test::expectSameBits;
using test::runCpu;

// β = 2e-5 s on the material sheet of support/material_scene.h (ω_max ≈ 1.05e4 1/s): the
// stiffest mode decays at βω²/2 ≈ 1.1e3 1/s, a tenth of its ω, while the swing of the sheet
// (ω ~ 10 1/s) is damped at 1e-3 1/s. Symplectic Euler at Δt = 1e-4 s stays inside
// ω²Δt² + 2βω²Δt ≈ 1.1 + 0.44 < 4.
constexpr double kBeta = 2e-5;

Scene dampedScene(Method method, double beta = kBeta, double dt = 1e-4) {
    Scene s = materialScene(method, dt);
    s.material->springDamping = beta;
    s.integrator.tolerance = 1e-12;
    s.integrator.maxIterations = 1000;
    return s;
}

// A 2×2 sheet pinned along its i = 0 side, with shear 0 so that only the structural springs are
// modelled: each free vertex moving along u is a mass m on one spring K along u (the spring
// along v joins the two free vertices, which move together, so it neither stretches nor
// damps), exactly linear: m x'' = −K x − βK x'. From x = 0, v = v0: x(t) = (v0/ω_d) e^{−γt}
// sin(ω_d t), γ = βK/(2m) = βω₀²/2, ω_d = √(ω₀² − γ²).
struct Oscillator {
    Scene scene;
    double k = 0, m = 0;
};
Oscillator dampedSpring(double beta, Method method, double dt) {
    Oscillator o;
    o.scene = parseScene(R"({
      "name": "damped spring",
      "cloth": { "resolution": [2, 2], "size": [0.1, 0.1], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 1, 0] },
      "gravity": [0, 0, 0],
      "pins": [[0, 0], [0, 1]],
      "integrator": { "method": "rk4", "dt": 0.0001 }
    })",
                         "damped spring (test)");
    Material mat;
    mat.density = 0.15;
    mat.stretch = 100;  // K = Y dv/du = 100 N/m along u for an inner spring
    mat.springDamping = beta;
    o.scene.material = mat;
    o.scene.integrator.method = method;
    o.scene.integrator.dt = dt;
    o.scene.integrator.tolerance = 1e-13;
    o.scene.integrator.maxIterations = 100;
    // Both springs along u lie on a border line (the sheet is one cell): each carries half the
    // cell, K/2 (docs/physics.md "Borders"), and its damping βK/2.
    o.k = 0.5 * o.scene.slotStiffness(0);
    o.m = o.scene.vertexMass(1, 0);
    return o;
}

// Largest |x(t_n) − closed form| over the run, over the initial amplitude v0/ω₀.
double oscillatorError(const Oscillator& o, Solver& solver, double v0, long steps, double beta) {
    SimState s = solver.read();
    s.velocities[1] = s.velocities[3] = {v0, 0, 0};
    solver.write(s);
    const double w0 = std::sqrt(o.k / o.m), gamma = beta * o.k / (2 * o.m);
    const double wd = std::sqrt(w0 * w0 - gamma * gamma), x0 = o.scene.cloth.size.x;
    double worst = 0;
    for (long n = 1; n <= steps; ++n) {
        EXPECT_FALSE(solver.step(1).unstable);
        const double t = n * o.scene.integrator.dt;
        const double x = v0 / wd * std::exp(-gamma * t) * std::sin(wd * t);
        const SimState now = solver.read();
        for (int k : {1, 3}) worst = std::max(worst, std::abs(now.positions[k].x - x0 - x));
    }
    return worst / (v0 / w0);
}

// RK4 at ω₀Δt ≈ 0.05: its global error after five periods is about N (ω₀Δt)⁵/120 ≈ 2e-6 of the
// amplitude, so 1e-5 holds it with room; getting γ wrong by 1% (0.05% of ω₀ here) shifts the
// amplitude by 1% of 1.6 = 1.6e-2 after five periods, far outside. The decay is βω₀²/2: at
// γ/ω₀ = βω₀/2 = 0.05 the amplitude falls to e^{−2π·5·0.05} ≈ 0.21 over the run.
TEST(SpringDamping, OneDampedSpringFollowsTheDampedOscillator) {
    const double dt = 1e-4;
    Oscillator o = dampedSpring(0, Method::Rk4, dt);
    const double w0 = std::sqrt(o.k / o.m), beta = 0.1 / w0;  // γ/ω₀ = βω₀/2 = 0.05
    o = dampedSpring(beta, Method::Rk4, dt);
    ASSERT_TRUE(Features::of(o.scene).springDamping);
    ASSERT_FALSE(Features::of(o.scene).shear);
    const long steps = std::lround(5 * 2 * std::numbers::pi / w0 / dt);
    for (Precision p : {Precision::Double}) {
        std::unique_ptr<Solver> solver = makeCpuSolver(o.scene, {p, 1});
        const double error = oscillatorError(o, *solver, 0.01, steps, beta);
        std::printf(
            "omega0 dt = %.3f, gamma/omega0 = %.3f, %ld steps: max error %.3g of the "
            "amplitude\n",
            w0 * dt, beta * w0 / 2, steps, error);
        EXPECT_LT(error, 1e-5);
        // Without damping the same run ends far from the damped solution: the test sees β.
        std::unique_ptr<Solver> undamped =
            makeCpuSolver(dampedSpring(0, Method::Rk4, dt).scene, {p, 1});
        EXPECT_GT(oscillatorError(o, *undamped, 0.01, steps, beta), 0.1);
    }
}

// Implicit Euler on the same spring: first order, and its own damping ~ω₀²Δt/2 adds to γ, so
// the error falls as Δt: halving Δt about halves it, and the amplitude never grows.
TEST(SpringDamping, ImplicitEulerConvergesOnTheDampedSpringAtFirstOrder) {
    Oscillator o = dampedSpring(0, Method::ImplicitEuler, 1e-4);
    const double w0 = std::sqrt(o.k / o.m), beta = 0.1 / w0;
    const double period = 2 * std::numbers::pi / w0;
    double previous = 0;
    for (double dt : {4e-5, 2e-5, 1e-5}) {
        o = dampedSpring(beta, Method::ImplicitEuler, dt);
        std::unique_ptr<Solver> solver = makeCpuSolver(o.scene, {Precision::Double, 1});
        const double error = oscillatorError(o, *solver, 0.01, std::lround(2 * period / dt), beta);
        std::printf("implicit Euler dt = %g: error %.4g of the amplitude\n", dt, error);
        EXPECT_EQ(solver->solveStats().misses, 0);
        if (previous > 0) {
            EXPECT_NEAR(previous / error, 2.0, 0.3);
        }
        previous = error;
    }
}

// Rigid motion stretches no spring, so the damping adds nothing: a uniform translation exactly,
// a rotation to rounding ((Ω × d)·d = 0). One explicit Euler step measures the force the
// solver applies, m (v₁ − v₀)/Δt, with and without β; a stretching field, for contrast, meets
// a damping force of its full size βK|Δv|.
TEST(SpringDamping, RigidMotionIsNotDamped) {
    Scene damped = dampedScene(Method::ExplicitEuler, 1e-3, 1e-6);
    damped.pins.clear();
    damped.wind.reset();
    damped.gravity = {0, 0, 0};
    damped.material->airDamping = 0;
    Scene plain = damped;
    plain.material->springDamping = 0;
    const Grid g = damped.grid();
    const glm::dvec3 centre = g.restPosition(g.nu / 2, g.nv / 2);
    const glm::dvec3 translation{0.3, -1.2, 0.7}, spin{2.0, -1.0, 3.0};  // [m/s], [rad/s]
    auto stepped = [&](const Scene& s, CpuIsa isa, auto field) {
        CpuSolver<double> solver(s, 1, isa);
        SimState st = solver.read();
        for (std::size_t k = 0; k < st.positions.size(); ++k)
            st.velocities[k] = field(st.positions[k]);
        solver.write(st);
        EXPECT_FALSE(solver.step(1).unstable);
        return solver.read();
    };
    auto dampingEffect = [&](auto field) {  // max |Δv(β) − Δv(0)|, the scalar path and the rows
        double worst = 0;
        for (CpuIsa isa : {CpuIsa::Scalar, CpuIsa::Auto}) {
            const SimState a = stepped(damped, isa, field), b = stepped(plain, isa, field);
            for (std::size_t k = 0; k < a.velocities.size(); ++k)
                worst = std::max(worst, glm::length(a.velocities[k] - b.velocities[k]));
        }
        return worst;
    };
    // What a non-rigid field of the same speeds meets: β K |Δv| / m Δt per spring, |Δv| ~ |Ω| L.
    const double k = damped.slotStiffness(0), m = damped.vertexMass(1, 1);
    const double scale =
        damped.integrator.dt * damped.material->springDamping * k * glm::length(spin) * g.du / m;
    const double translated = dampingEffect([&](const glm::dvec3&) { return translation; });
    const double rotated = dampingEffect(
        [&](const glm::dvec3& p) { return translation + glm::cross(spin, p - centre); });
    const double stretched = dampingEffect([&](const glm::dvec3& p) {
        return translation + glm::length(spin) * glm::dot(p - centre, g.u) * g.u;
    });
    std::printf("damping effect / scale: translation %.3g, rotation %.3g, stretching %.3g\n",
                translated / scale, rotated / scale, stretched / scale);
    EXPECT_EQ(translated, 0);
    EXPECT_LT(rotated, 1e-9 * scale);
    EXPECT_GT(stretched, 0.1 * scale);
}

// The 16×12 sheet is one band (bands are whole chunks of ~1024 vertices); the same cells on
// 48×80 vertices make 4 chunks, so 3 threads split it and read each other's border rows — the
// fused Euler sweep's old velocities among them (Verlet's gather and kick raced there until a
// barrier was put between them).
TEST(SpringDamping, EveryInstructionSetAndThreadCountGivesTheScalarPathsBits) {
    for (bool large : {false, true}) {
        for (Method method : kMethods) {
            // Explicit Euler is stable here only thanks to β: Δt < c/ω² + β (docs/stability.md).
            const double dt = method == Method::ExplicitEuler ? 1e-5 : 1e-4;
            Scene scene = dampedScene(method, kBeta, dt);
            scene.material->bend = 1e-4;  // the damping comes after the bending in both paths
            if (large) {
                scene.cloth.nu = 48;
                scene.cloth.nv = 80;
                scene.cloth.size = {47 * 0.08, 79 * 0.06};
            }
            const long steps = large ? test::sanitizedSteps(20, 5) : test::sanitizedSteps(60, 15);
            const SimState scalarF = runCpu<float>(scene, CpuIsa::Scalar, 1, steps);
            const SimState scalarD = runCpu<double>(scene, CpuIsa::Scalar, 1, steps);
            for (CpuIsa isa : {CpuIsa::Scalar, CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512}) {
                if (!cpuIsaSupported(isa)) continue;
                for (int threads : {1, 3}) {
                    if (isa == CpuIsa::Scalar && threads == 1) continue;  // the oracle itself
                    const std::string what = std::string(methodName(method)) + " " +
                                             cpuIsaName(isa) + " " + std::to_string(threads) +
                                             " threads" + (large ? " 48x80" : " 16x12");
                    expectSameBits(runCpu<float>(scene, isa, threads, steps), scalarF,
                                   what + " float");
                    expectSameBits(runCpu<double>(scene, isa, threads, steps), scalarD,
                                   what + " double");
                }
            }
        }
    }
}

// Against the reference in double, the tolerances of tests/cpu/bending_solver_test.cpp:
// rounding only, 1e-12 of the extent; implicit Euler's two CGs stop at |r| ≤ 1e-12|b|, 1e-9.
// The damping must have moved the sheet by far more: without it the reference ends more than
// 100× the tolerance away.
TEST(SpringDamping, TheCpuSolverMatchesTheReference) {
    for (Method method : kMethods) {
        // vbd's 10 iterations do not converge to its reference, backward Euler: its parity is
        // tests/cpu/vbd_test.cpp's, at convergence.
        if (method == Method::Vbd) continue;
        const bool explicitEuler = method == Method::ExplicitEuler;
        const Scene scene = dampedScene(method, kBeta, explicitEuler ? 1e-5 : 1e-4);
        const double extent = scene.grid().extent();
        const long steps = explicitEuler ? 3000 : 1000;
        std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 2});
        ASSERT_FALSE(solver->step(steps).unstable) << methodName(method);
        ref::Simulation sim(toReference(scene));
        Scene plain = scene;
        plain.material->springDamping = 0;
        ref::Simulation undamped(toReference(plain));
        for (long n = 0; n < steps; ++n) sim.step();
        bool undampedFinite = true;
        for (long n = 0; n < steps && undampedFinite; ++n) {
            undamped.step();
            undampedFinite = undamped.finiteAndBelowMaxSpeed();
        }
        const double tolerance = method == Method::ImplicitEuler ? 1e-9 : 1e-12;
        const double off = maxDeviationOverExtent(solver->read(), sim, extent);
        const double effect =
            undampedFinite ? maxDeviationOverExtent(solver->read(), undamped, extent) : INFINITY;
        std::printf("%-16s: %.3g off the reference, spring damping moved it %.3g\n",
                    methodName(method), off, effect);
        EXPECT_LT(off, tolerance) << methodName(method);
        EXPECT_GT(effect, 100 * tolerance) << methodName(method);
    }
}

// Implicit Euler at a Δt 100× beyond symplectic Euler's bound: every solve converges, the sheet
// stays finite, and the reference agrees.
TEST(SpringDamping, ImplicitEulerWithTheDampingJacobianConvergesAndIsStable) {
    Scene scene = dampedScene(Method::ImplicitEuler, 1e-3, 1e-3);
    scene.integrator.tolerance = 1e-8;
    scene.integrator.maxIterations = 2000;
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 1});
    ASSERT_FALSE(solver->step(200).unstable);
    const SolveStats& st = solver->solveStats();
    std::printf(
        "implicit Euler dt = 1e-3, beta = 1e-3: %ld solves, %.1f iterations each, most "
        "%d, %ld misses\n",
        st.solves, double(st.iterations) / double(st.solves), st.mostIterations, st.misses);
    EXPECT_EQ(st.misses, 0);
    ref::Simulation sim(toReference(scene));
    for (int n = 0; n < 200; ++n) sim.step();
    EXPECT_EQ(sim.cgStats().misses, 0);
    EXPECT_LT(maxDeviationOverExtent(solver->read(), sim, scene.grid().extent()), 1e-6);
}

// Spring damping only removes energy: with no drag, no wind and no gravity, a sheet set
// vibrating in its plane (its pins still) keeps its energy under RK4 at a small Δt without β (to
// 1e-4) and loses most of it with β, never gaining any from one step to the next beyond RK4's own
// 1e-9. (Motion across the flat sheet stretches no spring to first order, so it is not damped:
// docs/physics.md "Spring damping".)
TEST(SpringDamping, DissipatesEnergy) {
    Scene damped = dampedScene(Method::Rk4, kBeta, 1e-5);
    damped.wind.reset();
    damped.gravity = {0, 0, 0};
    damped.material->airDamping = 0;
    Scene plain = damped;
    plain.material->springDamping = 0;
    auto energies = [&](const Scene& s) {
        std::unique_ptr<Solver> solver = makeCpuSolver(s, {Precision::Double, 1});
        SimState st = solver->read();
        const Grid g = s.grid();
        for (std::size_t k = 0; k < st.velocities.size(); ++k)  // a rough in-plane vibration
            st.velocities[k] =
                0.01 * std::sin(1.7 * double(k)) * g.u + 0.02 * std::cos(0.9 * double(k)) * g.v;
        for (const Pin& p : s.pins) st.velocities[std::size_t(g.index(p.i, p.j))] = {0, 0, 0};
        solver->write(st);
        std::vector<double> e{energy(s, solver->read()).total()};
        for (int n = 0; n < 50; ++n) {
            EXPECT_FALSE(solver->step(20).unstable);
            e.push_back(energy(s, solver->read()).total());
        }
        return e;
    };
    const std::vector<double> a = energies(damped), b = energies(plain);
    std::printf("energy: start %.4g J; without beta %.4g J, with beta %.4g J after 1000 steps\n",
                a.front(), b.back(), a.back());
    EXPECT_NEAR(b.back(), b.front(), 1e-4 * b.front());
    EXPECT_LT(a.back(), 0.5 * a.front());
    for (std::size_t n = 1; n < a.size(); ++n) EXPECT_LE(a[n], a[n - 1] * (1 + 1e-9)) << n;
}

// docs/stability.md "Spring damping": at rest the damping matrix is β H, so a mode of ω² has the
// rate c + βω². Explicit Euler then has a bound, Δt < c/ω² + β (and (c + βω²)Δt < 2), where it
// had none at c ≈ 0; symplectic Euler's shrinks; β = 0 gives the undamped bounds' bits.
TEST(SpringDamping, StabilityBoundsFollowTheDampedRate) {
    const double w2 = 1e8, c = 0.1, beta = 2e-5;
    for (Method m : kMethods)
        EXPECT_EQ(dampedMethodDt(m, w2, c, 0), methodDt(m, w2, c)) << methodName(m);
    EXPECT_DOUBLE_EQ(dampedMethodDt(Method::ExplicitEuler, w2, c, beta),
                     std::min(c / w2 + beta, 2 / (c + beta * w2)));
    const double cw = c + beta * w2;
    EXPECT_DOUBLE_EQ(dampedMethodDt(Method::SymplecticEuler, w2, c, beta),
                     (-cw + std::sqrt(cw * cw + 4 * w2)) / w2);
    EXPECT_LT(dampedMethodDt(Method::SymplecticEuler, w2, c, beta),
              methodDt(Method::SymplecticEuler, w2, c));
    const StabilityBound b = estimateStability(dampedScene(Method::ExplicitEuler));
    EXPECT_EQ(b.springDamping, kBeta);
    EXPECT_GT(b.safeDt(Method::ExplicitEuler), 0.5 * kBeta);
    // The bound is real: explicit Euler at half of it is stable for 2000 steps, at twice it not.
    for (double factor : {0.5, 2.0}) {
        const double dt = factor * b.safeDt(Method::ExplicitEuler);
        std::unique_ptr<Solver> solver =
            makeCpuSolver(dampedScene(Method::ExplicitEuler, kBeta, dt), {Precision::Double, 1});
        const bool unstable = solver->step(2000).unstable;
        std::printf("explicit Euler at %.2g x the bound %.3g s: %s\n", factor,
                    b.safeDt(Method::ExplicitEuler), unstable ? "unstable" : "stable");
        EXPECT_EQ(unstable, factor > 1);
    }
}

}  // namespace
}  // namespace cloth
