// The renderer's CPU-side geometry: cloth triangles wound about the DESIGN.md §2 normal, chains
// as lines, the packed vec4 upload, the colliders' lit triangles.
#include "render/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "model/collider_mesh.h"

namespace cloth::render {
namespace {

SimState flatGrid(int nu, int nv) {
    SimState s{nu, nv, {}, {}};
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) s.positions.emplace_back(0.1 * i, 0.0, 0.2 * j);
    s.velocities.assign(s.positions.size(), glm::dvec3(0));
    return s;
}

TEST(ClothIndices, TwoTrianglesPerCellWoundAboutTheNormal) {
    const int nu = 5, nv = 3;  // not square, so i and j cannot be swapped unnoticed
    const ClothIndices c = clothIndices(nu, nv);
    EXPECT_FALSE(c.lines);
    ASSERT_EQ(c.indices.size(), std::size_t((nu - 1) * (nv - 1) * 6));
    const SimState s = flatGrid(nu, nv);  // û = x, v̂ = z: the normal û × v̂ is −y
    for (std::size_t t = 0; t < c.indices.size(); t += 3) {
        const glm::dvec3 a = s.positions[c.indices[t]], b = s.positions[c.indices[t + 1]],
                         d = s.positions[c.indices[t + 2]];
        const glm::dvec3 n = glm::cross(b - a, d - a);
        EXPECT_LT(n.y, 0) << "triangle " << t / 3;
        for (int v = 0; v < 3; ++v) EXPECT_LT(c.indices[t + v], std::uint32_t(nu * nv));
    }
}

TEST(ClothIndices, ChainsAreLineStripsInIndexOrder) {
    for (const auto& [nu, nv] : {std::pair{1, 3}, std::pair{4, 1}}) {
        const ClothIndices c = clothIndices(nu, nv);
        EXPECT_TRUE(c.lines);
        ASSERT_EQ(c.indices.size(), std::size_t(nu * nv));
        for (std::uint32_t k = 0; k < c.indices.size(); ++k) EXPECT_EQ(c.indices[k], k);
    }
}

TEST(PackCloth, PositionsAndUnitNormalsAsVec4) {
    std::vector<glm::vec4> p, n;
    ASSERT_TRUE(packCloth(flatGrid(4, 3), p, n));
    ASSERT_EQ(p.size(), 12u);
    EXPECT_FLOAT_EQ(p[5].x, 0.1f);  // k = 5: (i, j) = (1, 1)
    EXPECT_FLOAT_EQ(p[5].z, 0.2f);
    for (const glm::vec4& v : n) EXPECT_NEAR(v.y, -1.0f, 1e-6f);
}

TEST(PackCloth, RefusesANonFiniteState) {
    SimState s = flatGrid(3, 3);
    s.positions[4].y = std::numeric_limits<double>::quiet_NaN();
    std::vector<glm::vec4> p, n;
    EXPECT_FALSE(packCloth(s, p, n));
    s.positions[4].y = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(packCloth(s, p, n));
}

// A box keeps its edges sharp (every corner lit by its face's normal); a sphere is smooth (every
// corner lit within 3° of the radial direction, finer than its facets).
TEST(LitMesh, SharpBoxEdgesSmoothSphere) {
    const LitMesh box = litMesh(boxMesh({glm::dvec3(0), glm::dvec3(1, 0.5, 2), glm::dmat3(1)}));
    ASSERT_EQ(box.positions.size(), 36u);
    for (std::size_t k = 0; k < box.positions.size(); k += 3) {
        const glm::vec3 a = box.positions[k], b = box.positions[k + 1], c = box.positions[k + 2];
        const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
        for (std::size_t v = k; v < k + 3; ++v)
            EXPECT_NEAR(glm::dot(box.normals[v], face), 1, 1e-6);
        EXPECT_GT(glm::dot(face, a + b + c), 0) << "outward";
    }
    const LitMesh sphere = litMesh(sphereMesh({glm::dvec3(0), 1.0}, 2));
    for (std::size_t v = 0; v < sphere.positions.size(); ++v)
        EXPECT_GT(glm::dot(sphere.normals[v], sphere.positions[v]), std::cos(0.05));
}

}  // namespace
}  // namespace cloth::render
