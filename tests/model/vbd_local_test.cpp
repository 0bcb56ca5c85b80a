// model/vbd_local.h against the functions it stands beside: a spring's local gradient is minus
// springForce and its Hessian is the matrix springJacobianTimes applies (the same clamp), the
// bending diagonal is the Hessian's W_kk (the energy's second difference), and the Newton step
// of a quadratic local problem lands on its minimum.
#include "model/vbd_local.h"

#include <gtest/gtest.h>

namespace cloth {
namespace {

using V = Vec3<double>;

TEST(VbdLocal, ASpringsGradientIsMinusItsForceAndItsHessianIsImplicitEulersClampedJacobian) {
    const V pk(0.1, -0.2, 0.3);
    for (const V pq : {V(1.2, 0.4, -0.1), V(0.3, -0.1, 0.35)}) {  // stretched, then compressed
        VbdLocal<double> local;
        addVbdSpring(pk, pq, 700.0, 0.6, local);
        const V f = springForce(pk, pq, 700.0, 0.6);
        EXPECT_NEAR(glm::length(local.gradient + f), 0, 1e-12 * glm::length(f));
        for (const V w : {V(1, 0, 0), V(0, 1, 0), V(0, 0, 1), V(0.3, -2, 0.7)}) {
            const V expected = springJacobianTimes(pk, pq, 700.0, 0.6, w);
            EXPECT_NEAR(glm::length(local.hessian.matrix() * w - expected), 0,
                        1e-12 * (1 + glm::length(expected)));
        }
    }
}

// E = ½ xᵀ(W ⊗ I)x: the second derivative along x_k of E is W_kk, measured by differences of
// bendingEnergy on a random state, at a corner, an edge and inside.
TEST(VbdLocal, TheBendingDiagonalIsTheEnergysSecondDerivative) {
    Grid g;
    g.nu = 6;
    g.nv = 5;
    g.du = 0.1;
    g.dv = 0.12;
    const BendingWeights w = bendingWeights(g, 2e-3);
    std::vector<glm::dvec3> x(std::size_t(g.count()));
    for (std::size_t k = 0; k < x.size(); ++k)
        x[k] = glm::dvec3(0.1 * double(k % 7), 0.03 * double(k % 5), 0.2 * double(k % 3));
    for (const auto& [i, j] :
         {std::pair{0, 0}, std::pair{2, 0}, std::pair{3, 2}, std::pair{5, 4}}) {
        const std::size_t k = std::size_t(g.index(i, j));
        auto energyAt = [&](double dx) {
            std::vector<glm::dvec3> y = x;
            y[k].x += dx;
            return bendingEnergy(w, [&](int a, int b) { return y[std::size_t(g.index(a, b))]; });
        };
        const double e = 1e-3;
        const double second = (energyAt(e) - 2 * energyAt(0) + energyAt(-e)) / (e * e);
        EXPECT_NEAR(bendingDiagonal<double>(w, i, j), second, 1e-6 * second) << i << ", " << j;
    }
}

TEST(VbdLocal, TheNewtonStepOfAQuadraticLandsOnItsMinimum) {
    const V xn(0.2, 1.0, -0.3), y(0.25, 0.9, -0.3), grabTarget(0.5, 0.5, 0.5);
    V x = xn + V(0.01, -0.02, 0.0), d = x - xn;  // the iterate: position and displacement
    VbdLocal<double> local;
    addVbdInertia(d, y - xn, 0.01, 1.0 / 60, 2.0, local);
    addVbdGrab(x, grabTarget, 3.0, local);
    V s;
    ASSERT_TRUE(vbdNewtonStep(local, 0.01 * 3600, s));
    x += s;
    d += s;
    VbdLocal<double> after;  // the gradient at the new x vanishes
    addVbdInertia(d, y - xn, 0.01, 1.0 / 60, 2.0, after);
    addVbdGrab(x, grabTarget, 3.0, after);
    EXPECT_LT(glm::length(after.gradient), 1e-12);
}

// vbd's friction (vbdFrictionLane) is the gradient of D = w f0(|S u|), IPC's mollified Coulomb
// energy: f0(y) = y²/ε − y³/(3ε²) + ε/3 below ε, y above (f0' = f1). Checked against central
// differences of D in both regimes; no force along n; sliding, the force is Coulomb's w against
// the slide; the Hessian's added part is s S, s = w f1(|t|)/|t| (nothing along n).
TEST(VbdLocal, FrictionIsTheGradientOfTheMollifiedCoulombEnergy) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));
    const double w = 0.7, eps = 1e-3;
    const auto energy = [&](const glm::dvec3& u) {
        const glm::dvec3 t = u - glm::dot(u, n) * n;
        const double y = glm::length(t);
        return w * (y < eps ? y * y / eps - y * y * y / (3 * eps * eps) + eps / 3 : y);
    };
    for (double scale : {0.3e-3, 0.8e-3, 5e-3, 0.2}) {  // stuck, stuck, sliding, sliding
        const glm::dvec3 u = scale * glm::normalize(glm::dvec3(1.0, 0.4, 0.7)) + 0.01 * n;
        VbdLocal<double> local;
        addVbdFriction(u, n, w, eps, local);
        const double step = 1e-6 * eps;
        for (int c = 0; c < 3; ++c) {
            glm::dvec3 e(0);
            e[c] = step;
            const double numeric = (energy(u + e) - energy(u - e)) / (2 * step);
            EXPECT_NEAR(local.gradient[c], numeric, 1e-6 * w) << "scale " << scale << " axis " << c;
        }
        EXPECT_NEAR(glm::dot(local.gradient, n), 0, 1e-12) << scale;
        if (scale > eps) {
            EXPECT_NEAR(glm::length(local.gradient), w, 1e-12) << scale;
        }
        const VbdLane<double> a = vbdLane(local);
        EXPECT_NEAR(vbdNormalStiffness(a, n.x, n.y, n.z), 0, 1e-9 * local.hessian.xx) << scale;
        const glm::dvec3 t = u - glm::dot(u, n) * n;
        EXPECT_NEAR(
            vbdNormalStiffness(a, t.x / glm::length(t), t.y / glm::length(t), t.z / glm::length(t)),
            glm::length(local.gradient) / glm::length(t), 1e-9 * local.hessian.xx)
            << scale;
    }
}

}  // namespace
}  // namespace cloth
