// The collider meshes shared by the export and the renderer: every closed one is closed,
// manifold and oriented outwards (positive volume, winding number +1 inside), with its vertices
// on the shape's surface (φ = 0).
#include "model/collider_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cloth {
namespace {

using D3 = glm::dvec3;

double volume(const TriMesh& m) {  // Σ ⟨a, b × c⟩ / 6: positive when counter-clockwise outside
    double v = 0;
    for (const auto& t : m.triangles)
        v += glm::dot(m.vertices[t[0]], glm::cross(m.vertices[t[1]], m.vertices[t[2]])) / 6;
    return v;
}

template <typename Shape>
void expectClosedOutwardOnSurface(const TriMesh& m, const Shape& shape, const D3& inside,
                                  double volumeWant, double volumeTol) {
    EXPECT_EQ(closedManifoldProblem(m), std::nullopt);
    EXPECT_NEAR(volume(m), volumeWant, volumeTol);
    EXPECT_NEAR(windingNumber(m, inside), 1, 1e-9);
    for (const D3& v : m.vertices) EXPECT_NEAR(contact(shape, v).phi, 0, 1e-12);
}

TEST(ColliderMesh, BoxIsClosedOutwardAndExact) {
    const BoxT<double> box{{0.3, 0.1, -0.2}, {0.4, 0.2, 0.1}, axisAngle(D3(0, 0.6, 0.8), 0.9)};
    const TriMesh m = boxMesh(box);
    EXPECT_EQ(m.triangles.size(), 12u);
    expectClosedOutwardOnSurface(m, box, box.center, 8 * 0.4 * 0.2 * 0.1, 1e-12);
}

TEST(ColliderMesh, IcosphereIsClosedOutwardOnTheSphere) {
    const SphereT<double> s{{0.2, -0.1, 0.4}, 0.7};
    const TriMesh m = sphereMesh(s, 3);
    EXPECT_EQ(m.triangles.size(), 20u * 64u);
    const double v = 4.0 / 3 * std::numbers::pi * std::pow(0.7, 3);
    expectClosedOutwardOnSurface(m, s, s.center, v, 0.03 * v);  // inscribed: slightly less
}

TEST(ColliderMesh, CapsuleIsClosedOutwardOnTheCapsule) {
    const CapsuleT<double> c{{0.1, 0.2, 0.3}, {0.6, -0.4, 0.5}, 0.2};
    const TriMesh m = capsuleMesh(c, 24, 8);
    const double len = glm::length(c.b - c.a), r = c.radius;
    const double v = std::numbers::pi * r * r * len + 4.0 / 3 * std::numbers::pi * r * r * r;
    expectClosedOutwardOnSurface(m, c, 0.5 * (c.a + c.b), v, 0.03 * v);
}

TEST(ColliderMesh, PlaneQuadLiesOnThePlaneFacingItsNormal) {
    const PlaneT<double> p{{0, 1, 0}, glm::normalize(D3(1, 1, 0))};
    const TriMesh m = planeQuad(p, 5);
    for (const D3& v : m.vertices) EXPECT_NEAR(contact(p, v).phi, 0, 1e-12);
    for (const auto& t : m.triangles) {
        const D3 n =
            glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
        EXPECT_NEAR(glm::dot(glm::normalize(n), p.normal), 1, 1e-12);
        EXPECT_NEAR(glm::length(n), 100, 1e-9);  // |a × b| = 2·area, area = half of 10 × 10
    }
}

}  // namespace
}  // namespace cloth
