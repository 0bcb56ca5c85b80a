// Checks of the reference's five integrators (tests/reference, docs/integrators.md) against
// closed forms and hand-worked updates, so that the oracle the backends are compared with is
// itself trusted: one step of each scheme on a linear spring, written out in scalars; the
// convergence order of each against the damped spring's closed form; the Hessian against finite
// differences of the forces; pins and colliders held in every scheme; a CG miss counted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "support/damped_spring.h"

namespace cloth {
namespace {

using ref::Method;

constexpr Method kAllMethods[] = {Method::ExplicitEuler, Method::SymplecticEuler,
                                  Method::Verlet,        Method::Rk4,
                                  Method::ImplicitEuler, Method::BackwardEuler};

const char* nameOf(Method m) {
    switch (m) {
        case Method::ExplicitEuler:
            return "explicit_euler";
        case Method::SymplecticEuler:
            return "symplectic_euler";
        case Method::Verlet:
            return "verlet";
        case Method::Rk4:
            return "rk4";
        case Method::ImplicitEuler:
            return "implicit_euler";
        case Method::BackwardEuler:
            return "backward_euler";
    }
    return "?";
}

// The seed's 1×2 spring along −y: vertex (0, 0) on top, pinned; (0, 1) hangs 1 m below it.
ref::Params verticalSpring(const DampedSpring& s, Method method, double dt) {
    ref::Params p;
    p.nu = 1;
    p.nv = 2;
    p.sizeV = 1;
    p.vAxis = {0, -1, 0};
    p.kStructural = s.k;
    p.damping = s.mu;
    p.mass = s.m;
    p.gravity = {0, -s.g, 0};
    p.pins = {{0, 0}};
    p.method = method;
    p.dt = dt;
    p.cgTolerance = 1e-14;  // the 3×3 system is solved exactly in two iterations anyway
    return p;
}

// A spring started at stretch x0 with stretch rate x'0 (the free vertex at y = −1 − x0).
ref::Simulation startedSpring(const DampedSpring& s, Method method, double dt, double x0,
                              double xDot0) {
    ref::Simulation sim(verticalSpring(s, method, dt));
    sim.setState({{0, 0, 0}, {0, -1 - x0, 0}}, {{0, 0, 0}, {0, -xDot0, 0}});
    return sim;
}

// One step of each scheme for x'' = a(x, x') = −ω² x − c x' (no gravity), as the page writes it.
void scalarStep(Method method, double w2, double c, double h, double& x, double& v) {
    auto a = [&](double xs, double vs) { return -w2 * xs - c * vs; };
    switch (method) {
        case Method::ExplicitEuler: {
            const double vOld = v;
            v += h * a(x, v);
            x += h * vOld;
            break;
        }
        case Method::SymplecticEuler:
            v += h * a(x, v);
            x += h * v;
            break;
        case Method::Verlet: {
            const double vHalf = v + h / 2 * a(x, v);
            x += h * vHalf;
            v = (vHalf + h / 2 * (-w2 * x)) / (1 + h * c / 2);
            break;
        }
        case Method::Rk4: {
            const double k1x = v, k1v = a(x, v);
            const double k2x = v + h / 2 * k1v, k2v = a(x + h / 2 * k1x, v + h / 2 * k1v);
            const double k3x = v + h / 2 * k2v, k3v = a(x + h / 2 * k2x, v + h / 2 * k2v);
            const double k4x = v + h * k3v, k4v = a(x + h * k3x, v + h * k3v);
            x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
            v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
            break;
        }
        case Method::ImplicitEuler:
        case Method::BackwardEuler:
            // v1 = v0 + h a(x1, v1), x1 = x0 + h v1, solved: exact for a linear spring, which the
            // linearisation at x_n reproduces (the axial stiffness is K whatever the stretch);
            // backward Euler's Newton solves the same linear equation.
            v = (v - h * w2 * x) / (1 + h * c + h * h * w2);
            x += h * v;
            break;
    }
}

// Each scheme's update is the one docs/integrators.md writes: three large steps (ω h = 0.35) of
// the reference on the spring's axis equal the scalar transcription to rounding.
TEST(ReferenceIntegrators, OneStepOfEachSchemeMatchesItsUpdateByHand) {
    const DampedSpring s{50, 0.8, 2, 0};  // no gravity: ω² = 25, c = 0.4
    const double h = 0.07, x0 = 0.1, v0 = 0.3;
    for (Method method : kAllMethods) {
        ref::Simulation sim = startedSpring(s, method, h, x0, v0);
        double x = x0, v = v0;
        for (int n = 0; n < 3; ++n) {
            sim.step();
            scalarStep(method, s.k / s.m, s.mu / s.m, h, x, v);
            const ref::V3 p = sim.positions()[1], u = sim.velocities()[1];
            EXPECT_NEAR(-p[1] - 1, x, 1e-15) << nameOf(method) << ", step " << n + 1;
            EXPECT_NEAR(-u[1], v, 1e-14) << nameOf(method) << ", step " << n + 1;
            EXPECT_EQ(p[0], 0);
            EXPECT_EQ(p[2], 0);
            EXPECT_EQ(sim.positions()[0], (ref::V3{0, 0, 0}));  // the pin
        }
    }
}

// verlet's colliders act after the drift, before the second kick (docs/integrators.md): a vertex
// resting on a floor ends each step on it with the inward velocity g h/2 of that kick.
TEST(ReferenceIntegrators, VerletEndsARestingStepWithHalfAKickIntoTheFloor) {
    ref::Params p;
    p.nu = 1;
    p.nv = 1;
    p.method = Method::Verlet;
    p.dt = 0.01;
    ref::Collider floor;
    floor.plane = {{0, 0, 0}, {0, 1, 0}};
    p.colliders = {floor};
    ref::Simulation sim(p);  // the one vertex starts on the floor, at rest
    for (int n = 0; n < 5; ++n) {
        sim.step();
        EXPECT_EQ(sim.positions()[0], (ref::V3{0, 0, 0}));
        EXPECT_DOUBLE_EQ(sim.velocities()[0][1], -9.81 * 0.01 / 2);
    }
}

// Error at time T against the closed form, with step h.
double springError(const DampedSpring& s, Method method, double h, double T) {
    const long steps = std::lround(T / h);
    ref::Simulation sim = startedSpring(s, method, h, s.stretch0, 0);
    for (long n = 0; n < steps; ++n) sim.step();
    return s.error(double(steps) * h, -sim.positions()[1][1] - 1, -sim.velocities()[1][1]);
}

// The scheme a scene names (docs/integrators.md), as the reference spells it.
Method methodNamed(const char* name) {
    for (Method m : kAllMethods)
        if (std::string(name) == nameOf(m)) return m;
    ADD_FAILURE() << "no reference scheme named " << name;
    return Method::ExplicitEuler;
}

// The observed order log2(e(h)/e(h/2)) at a fixed time is each scheme's order of accuracy: the
// damped spring hanging under gravity from rest, and stretched without gravity.
TEST(ReferenceIntegrators, DampedSpringConvergenceOrderOfEachScheme) {
    for (const DampedSpring& s : kOrderSprings) {
        for (const OrderCase& c : kOrderCases) {
            const Method method = methodNamed(c.method);
            const ObservedOrders r = observedOrders(
                c.h, [&](double h) { return springError(s, method, h, kOrderTime); });
            std::printf("reference %-16s g = %4.2f: errors %.3e %.3e %.3e, orders %.3f %.3f\n",
                        c.method, s.g, r.e1, r.e2, r.e4, r.o1, r.o2);
            EXPECT_NEAR(r.o1, c.order, 0.3) << c.method << ", g = " << s.g;
            EXPECT_NEAR(r.o2, c.order, 0.3) << c.method << ", g = " << s.g;
        }
    }
}

// A 4×3 cloth with every spring family and a pinned corner, in a state given by `scale` (1.1:
// every spring stretched; 0.9: every spring compressed) plus a small ripple.
ref::Simulation deformedCloth(double scale) {
    ref::Params p;
    p.nu = 4;
    p.nv = 3;
    p.sizeU = 1.5;
    p.sizeV = 1;
    p.kStructural = 30;
    p.kShear = 7;
    p.kBend = 2;
    p.pins = {{0, 0}};
    ref::Simulation sim(p);
    std::vector<ref::V3> x = sim.positions();
    for (std::size_t k = 0; k < x.size(); ++k) {
        for (int c = 0; c < 3; ++c) x[k][c] = scale * x[k][c] + 0.01 * std::sin(1.7 * k + 2.3 * c);
    }
    sim.setState(x, std::vector<ref::V3>(x.size(), ref::V3{0, 0, 0}));
    return sim;
}

std::vector<ref::V3> rippleDirection(const ref::Simulation& sim) {
    std::vector<ref::V3> w(sim.positions().size());
    for (std::size_t k = 0; k < w.size(); ++k) {
        for (int c = 0; c < 3; ++c) w[k][c] = sim.isPinned(int(k)) ? 0 : std::cos(0.9 * k + c);
    }
    return w;
}

// H = −∂F/∂x: with every spring stretched the clamp max(0, 1 − L/l) is inactive, and H w equals
// the central difference −(F(x + εw) − F(x − εw))/2ε to O(ε²) (pinned rows and columns removed).
TEST(ReferenceIntegrators, HessianProductIsMinusTheForceJacobianWhenStretched) {
    const ref::Simulation sim = deformedCloth(1.1);
    const std::vector<ref::V3> x = sim.positions(), w = rippleDirection(sim);
    const double eps = 1e-6;
    std::vector<ref::V3> xp = x, xm = x;
    for (std::size_t k = 0; k < x.size(); ++k) {
        for (int c = 0; c < 3; ++c) {
            xp[k][c] += eps * w[k][c];
            xm[k][c] -= eps * w[k][c];
        }
    }
    const std::vector<ref::V3> fp = sim.forces(xp), fm = sim.forces(xm);
    const std::vector<ref::V3> hw = sim.hessianProduct(x, w);
    double worst = 0, size = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        for (int c = 0; c < 3; ++c) {
            const double fd = sim.isPinned(int(k)) ? 0 : -(fp[k][c] - fm[k][c]) / (2 * eps);
            worst = std::fmax(worst, std::fabs(hw[k][c] - fd));
            size = std::fmax(size, std::fabs(fd));
        }
    }
    std::printf("|H w + dF/dx w| = %.3g of %.3g\n", worst, size);
    EXPECT_GT(size, 1);
    EXPECT_LT(worst, 1e-7 * size);
}

// Compressed springs make the exact Jacobian indefinite: for one spring compressed to l = L/2, a
// transverse probe e (vertex 1 moved by e, vertex 0 by −e) gives −w·(∂F/∂x)w = K (1 − L/l)|2e|²
// < 0. The clamp max(0, 1 − L/l) (Choi & Ko 2002) removes that term, H w = 0 there, and on a
// compressed cloth w·Hw ≥ 0 for every probe: implicit Euler's matrix stays SPD.
TEST(ReferenceIntegrators, ClampedHessianStaysPositiveUnderCompression) {
    ref::Params p;  // a free 2×1 spring along x, L = 1
    p.kStructural = 10;
    ref::Simulation spring(p);
    const std::vector<ref::V3> x = {{0, 0, 0}, {0.5, 0, 0}};
    const std::vector<ref::V3> w = {{0, -1, 0}, {0, 1, 0}};
    const double eps = 1e-6;
    const std::vector<ref::V3> fp = spring.forces({{0, -eps, 0}, {0.5, eps, 0}});
    const std::vector<ref::V3> fm = spring.forces({{0, eps, 0}, {0.5, -eps, 0}});
    double exact = 0;
    for (int k = 0; k < 2; ++k) {
        for (int c = 0; c < 3; ++c) exact -= w[k][c] * (fp[k][c] - fm[k][c]) / (2 * eps);
    }
    EXPECT_NEAR(exact, 10 * (1 - 1 / 0.5) * 4, 1e-6);
    const std::vector<ref::V3> hw = spring.hessianProduct(x, w);
    EXPECT_EQ(hw[0], (ref::V3{0, 0, 0}));
    EXPECT_EQ(hw[1], (ref::V3{0, 0, 0}));

    const ref::Simulation cloth = deformedCloth(0.9);
    const std::vector<ref::V3> y = cloth.positions();
    for (int probe = 0; probe < 20; ++probe) {
        std::vector<ref::V3> u(y.size());
        for (std::size_t k = 0; k < u.size(); ++k) {
            for (int c = 0; c < 3; ++c)
                u[k][c] = cloth.isPinned(int(k)) ? 0 : std::sin(3.1 * probe + 1.3 * k + 0.7 * c);
        }
        const std::vector<ref::V3> hu = cloth.hessianProduct(y, u);
        double uhu = 0;
        for (std::size_t k = 0; k < u.size(); ++k) {
            for (int c = 0; c < 3; ++c) uhu += u[k][c] * hu[k][c];
        }
        EXPECT_GE(uhu, 0) << "probe " << probe;
    }
}

// A small cloth with a floor and a sphere it falls onto: in every scheme, pinned vertices stay
// exactly at rest and no vertex ends a step inside a collider (DESIGN.md §2).
TEST(ReferenceIntegrators, EverySchemeHoldsPinsAndColliders) {
    for (Method method : kAllMethods) {
        ref::Params p;
        p.nu = 6;
        p.nv = 5;
        p.sizeU = 1;
        p.sizeV = 0.8;
        p.origin = {-0.5, 0.9, -0.4};
        p.kStructural = 200;
        p.kShear = 50;
        p.kBend = 10;
        p.damping = 0.5;
        p.mass = 0.1;
        p.pins = {{0, 0}, {-1, 0}};
        ref::Collider floor, ball;
        floor.plane = {{0, 0.3, 0}, {0, 1, 0.1}};
        ball.isSphere = true;
        ball.sphere = {{0.1, 0.7, 0.1}, 0.25};
        p.colliders = {floor, ball};
        p.method = method;
        p.dt = 2e-3;
        ref::Simulation sim(p);
        const std::vector<ref::V3> start = sim.positions();
        for (int n = 0; n < 500; ++n) {
            sim.step();
            ASSERT_TRUE(sim.finiteAndBelowMaxSpeed()) << nameOf(method) << ", step " << n + 1;
            for (std::size_t k = 0; k < start.size(); ++k) {
                const ref::V3& x = sim.positions()[k];
                if (sim.isPinned(int(k))) {
                    ASSERT_EQ(x, start[k]) << nameOf(method);
                    ASSERT_EQ(sim.velocities()[k], (ref::V3{0, 0, 0})) << nameOf(method);
                }
                const double toPlane = ((x[1] - 0.3) + 0.1 * x[2]) / std::sqrt(1.01);
                const double r =
                    std::sqrt((x[0] - 0.1) * (x[0] - 0.1) + (x[1] - 0.7) * (x[1] - 0.7) +
                              (x[2] - 0.1) * (x[2] - 0.1));
                ASSERT_GE(toPlane, -1e-12) << nameOf(method) << ", vertex " << k;
                ASSERT_GE(r - 0.25, -1e-12) << nameOf(method) << ", vertex " << k;
            }
        }
        EXPECT_NE(sim.positions()[7], start[7]) << nameOf(method);
    }
}

// A conjugate gradient capped below what the system needs stops with its last iterate and is
// counted as a miss with its residual (docs/integrators.md: never silent); a loose cap is not.
TEST(ReferenceIntegrators, CappedConjugateGradientCountsItsMisses) {
    auto run = [](int cap, double tol) {
        ref::Params q;
        q.nu = 5;
        q.nv = 4;
        q.kStructural = 1e4;
        q.kShear = 1e3;
        q.damping = 0.1;
        q.pins = {{0, 0}};
        q.method = Method::ImplicitEuler;
        q.dt = 0.01;  // h² K / m = 1: a system CG needs several iterations for
        q.cgTolerance = tol;
        q.cgMaxIterations = cap;
        ref::Simulation sim(q);
        std::vector<ref::V3> x = sim.positions();  // rippled, so that every solve is hard
        for (std::size_t k = 1; k < x.size(); ++k) x[k][1] += 0.05 * std::sin(2.1 * k);
        sim.setState(x, std::vector<ref::V3>(x.size(), ref::V3{0, 0, 0}));
        for (int n = 0; n < 10; ++n) sim.step();
        EXPECT_TRUE(sim.finiteAndBelowMaxSpeed());
        return sim.cgStats();
    };
    const ref::CgStats capped = run(2, 1e-12);
    EXPECT_EQ(capped.solves, 10);
    EXPECT_EQ(capped.misses, 10);
    EXPECT_EQ(capped.iterations, 20);
    EXPECT_GT(capped.worstResidual, 1e-12);
    const ref::CgStats full = run(500, 1e-12);
    std::printf("CG: capped at 2 -> worst residual %.3g; uncapped: %d iterations, residual %.3g\n",
                capped.worstResidual, full.lastIterations, full.lastResidual);
    EXPECT_EQ(full.misses, 0);
    EXPECT_GT(full.lastIterations, 2);
    EXPECT_LE(full.lastResidual, 1e-12);
}

}  // namespace
}  // namespace cloth
