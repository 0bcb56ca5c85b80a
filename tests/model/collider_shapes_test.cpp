// The collider shapes of docs/colliders.md §1: each φ is a signed distance (zero on the surface,
// negative inside, 1-Lipschitz, |∇φ| = 1 where smooth) and n is its gradient.
#include "model/collider_shapes.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "support/draws.h"

namespace cloth {
namespace {

using D3 = glm::dvec3;

BoxT<double> tiltedBox() {
    return {{0.3, -0.2, 0.5}, {0.4, 0.1, 0.25}, axisAngle(glm::normalize(D3(1, 2, -0.5)), 0.7)};
}

D3 randomPoint(std::mt19937& rng, double spread) {
    std::uniform_real_distribution<double> u(-spread, spread);
    return {u(rng), u(rng), u(rng)};
}

// ∇φ by central differences; where φ is smooth it equals n.
template <typename Shape>
D3 numericGradient(const Shape& s, const D3& p, double h = 1e-6) {
    D3 g;
    for (int a = 0; a < 3; ++a) {
        D3 e(0);
        e[a] = h;
        g[a] = (contact(s, p + e).phi - contact(s, p - e).phi) / (2 * h);
    }
    return g;
}

// Law: Rodrigues' matrix is orthonormal with determinant 1, fixes its axis and turns
// right-handed.
TEST(AxisAngle, IsARotationThatFixesItsAxis) {
    const D3 axis = glm::normalize(D3(0.3, -1, 2));
    const glm::dmat3 r = axisAngle(axis, 1.234);
    const glm::dmat3 id = glm::transpose(r) * r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(id[i][j], i == j ? 1 : 0, 1e-15);
    EXPECT_NEAR(glm::determinant(r), 1, 1e-15);
    EXPECT_NEAR(glm::length(r * axis - axis), 0, 1e-15);
    // Right-handed: 90° about z takes x to y.
    const D3 y = axisAngle(D3(0, 0, 1), std::numbers::pi / 2) * D3(1, 0, 0);
    EXPECT_NEAR(glm::length(y - D3(0, 1, 0)), 0, 1e-15);
}

// Law: the box SDF is 0 on a face, the distance along the face normal outside, minus the
// distance to the nearest face inside, and the distance to the corner beyond a corner.
TEST(BoxSdf, ZeroOnFacesNegativeInsideAndExactAlongTheNormal) {
    const BoxT<double> box = tiltedBox();
    const D3 ex = box.rotation[0], ey = box.rotation[1];
    // A face centre, a point 0.1 outside it, and the centre (distance to the nearest face y).
    EXPECT_NEAR(contact(box, box.center + 0.4 * ex).phi, 0, 1e-15);
    EXPECT_NEAR(contact(box, box.center + 0.5 * ex).phi, 0.1, 1e-15);
    EXPECT_NEAR(glm::length(contact(box, box.center + 0.5 * ex).normal - ex), 0, 1e-15);
    const ContactT<double> c = contact(box, box.center);
    EXPECT_NEAR(c.phi, -0.1, 1e-15);
    EXPECT_NEAR(std::abs(glm::dot(c.normal, ey)), 1, 1e-15);
    // Beyond a corner the distance is to the corner and n points away from it.
    const D3 corner = box.center + box.rotation * box.halfExtents;
    const D3 dir = glm::normalize(box.rotation * D3(1, 1, 1));
    const ContactT<double> cc = contact(box, corner + 0.2 * dir);
    EXPECT_NEAR(cc.phi, 0.2, 1e-14);
    EXPECT_NEAR(glm::length(cc.normal - dir), 0, 1e-14);
}

// Law: a signed distance is 1-Lipschitz and its gradient has unit length and equals n wherever
// it is differentiable (random points are almost surely off the medial surface).
template <typename Shape>
void expectSignedDistance(const Shape& s, double spread) {
    std::mt19937 rng(7);
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
        const D3 p = randomPoint(rng, spread), q = randomPoint(rng, spread);
        EXPECT_LE(std::abs(contact(s, p).phi - contact(s, q).phi),
                  glm::length(p - q) * (1 + 1e-12));
        const ContactT<double> c = contact(s, p);
        EXPECT_NEAR(glm::length(c.normal), 1, 1e-12);
        const D3 g = numericGradient(s, p);
        if (std::abs(glm::length(g) - 1) > 1e-6) continue;  // straddles a kink of φ
        EXPECT_NEAR(glm::length(g - c.normal), 0, 1e-6) << "at " << p.x << " " << p.y << " " << p.z;
        ++checked;
    }
    EXPECT_GT(checked, 1900);
}

TEST(BoxSdf, IsASignedDistanceWithItsGradientAsNormal) {
    expectSignedDistance(tiltedBox(), 1.0);
}

TEST(CapsuleSdf, IsASignedDistanceWithItsGradientAsNormal) {
    expectSignedDistance(CapsuleT<double>{{-0.3, 0.1, 0}, {0.4, 0.5, -0.2}, 0.15}, 1.0);
}

// Law: φ = distance to the segment − R beside the cylinder, beyond an end, inside a cap and on
// the axis (where n is unit and perpendicular to the axis).
TEST(CapsuleSdf, DistanceToTheSegmentMinusTheRadius) {
    const CapsuleT<double> cap{{0, 0, 0}, {0, 1, 0}, 0.2};
    EXPECT_NEAR(contact(cap, D3(0.5, 0.5, 0)).phi, 0.3, 1e-15);  // beside the cylinder
    EXPECT_NEAR(contact(cap, D3(0, 1.5, 0)).phi, 0.3, 1e-15);    // beyond the end b
    EXPECT_NEAR(contact(cap, D3(0, -0.1, 0)).phi, -0.1, 1e-15);  // inside the cap at a
    const ContactT<double> axis = contact(cap, D3(0, 0.5, 0));   // on the axis itself
    EXPECT_NEAR(axis.phi, -0.2, 1e-15);
    EXPECT_NEAR(glm::length(axis.normal), 1, 1e-15);
    EXPECT_NEAR(glm::dot(axis.normal, D3(0, 1, 0)), 0, 1e-15);  // perpendicular to the axis
}

// A grid sampled from a linear function reproduces it exactly (trilinear interpolation is exact
// for affine functions), with its constant gradient, anywhere inside the grid.
TEST(GridSdf, TrilinearIsExactForAnAffineFieldAndClampsOutside) {
    SdfGrid g;
    g.origin = {-1, -1, -1};
    g.cell = 0.25;
    g.count = {9, 9, 9};
    const D3 a = glm::normalize(D3(1, -2, 0.5));
    for (int k = 0; k < 9; ++k)
        for (int j = 0; j < 9; ++j)
            for (int i = 0; i < 9; ++i)
                g.values.push_back(glm::dot(a, g.origin + g.cell * D3(i, j, k)) - 0.1);
    const glm::dmat3 r = axisAngle(glm::normalize(D3(0, 1, 1)), 0.5);
    const SdfColliderT<double> c{&g, r, D3(2, 0, 0)};
    std::mt19937 rng(3);
    for (int n = 0; n < 500; ++n) {
        const D3 local = randomPoint(rng, 1.0);
        const ContactT<double> s = contact(c, r * local + D3(2, 0, 0));
        EXPECT_NEAR(s.phi, glm::dot(a, local) - 0.1, 1e-13);
        EXPECT_NEAR(glm::length(s.normal - r * a), 0, 1e-13);
    }
    // The far corner of the grid, and 1 m beyond it: φ grows by the distance to the grid.
    const D3 corner(1, 1, 1);
    EXPECT_NEAR(contact(c, r * (corner + D3(1, 0, 0)) + D3(2, 0, 0)).phi,
                contact(c, r * corner + D3(2, 0, 0)).phi + 1, 1e-13);
}

// Law: sampling in float gives the double value to float rounding (1e-5 on values of order 1).
TEST(GridSdf, FloatAgreesWithDouble) {
    SdfGrid g;
    g.origin = {0, 0, 0};
    g.cell = 0.1;
    g.count = {4, 5, 6};
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int n = 0; n < 4 * 5 * 6; ++n) g.values.push_back(u(rng));
    const SdfColliderT<double> cd{&g};
    const SdfColliderT<float> cf{&g};
    for (int n = 0; n < 200; ++n) {
        const D3 p = D3(0.3, 0.4, 0.5) * (test::drawVec3(u, rng) + 1.0) / 2.0;
        EXPECT_NEAR(contact(cf, glm::vec3(p)).phi, contact(cd, p).phi, 1e-5);
    }
}

}  // namespace
}  // namespace cloth
