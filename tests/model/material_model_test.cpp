// What the solvers model of a material scene, from the Scene accessors (model/scene.h): the
// lumped masses, the springs of each slot, and the stability bound over the vertices' own masses.
#include <gtest/gtest.h>

#include "model/stability.h"
#include "model/stiffness.h"
#include "model/vertex_masses.h"
#include "support/material_scene.h"

namespace cloth {
namespace {

TEST(MaterialModel, VertexMassesSumToDensityTimesAreaAboutTheCentroid) {
    const Scene s = materialScene(Method::SymplecticEuler);
    const Grid g = s.grid();
    const std::vector<double> m = vertexMasses(s);
    double total = 0;
    glm::dvec3 moment(0);
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            total += m[std::size_t(g.index(i, j))];
            moment += m[std::size_t(g.index(i, j))] * g.restPosition(i, j);
        }
    const double area = s.cloth.size.x * s.cloth.size.y;
    EXPECT_NEAR(total, s.material->density * area, 1e-14 * total);
    EXPECT_NEAR(s.totalMass(), total, 1e-14 * total);
    const glm::dvec3 centroid = g.origin + 0.5 * s.cloth.size.x * g.u + 0.5 * s.cloth.size.y * g.v;
    EXPECT_LT(glm::length(moment / total - centroid), 1e-14 * g.extent());
    const double cell = s.material->density * g.du * g.dv;
    EXPECT_DOUBLE_EQ(s.vertexMass(0, 0), cell / 4);
    EXPECT_DOUBLE_EQ(s.vertexMass(3, 0), cell / 2);
    EXPECT_DOUBLE_EQ(s.vertexMass(0, 5), cell / 2);
    EXPECT_DOUBLE_EQ(s.vertexMass(3, 5), cell);
}

// du ≠ dv: the structural springs along u and along v differ, each pair ±(di, dj) alike; the
// shear springs are all one K; the bend slots are 0, and the family is not modelled.
TEST(MaterialModel, EachSlotHasTheStiffnessOfItsDirection) {
    const Scene s = materialScene(Method::SymplecticEuler);
    const Grid g = s.grid();
    ASSERT_NE(g.du, g.dv);
    const MembraneSprings k = membraneSprings(*s.material, g.du, g.dv);
    EXPECT_NE(k.alongU, k.alongV);
    for (std::size_t slot = 0; slot < kSpringOffsets.size(); ++slot) {
        const SpringOffset& o = kSpringOffsets[slot];
        const double expected = o.family == Family::Bend    ? 0
                                : o.family == Family::Shear ? k.shear
                                : o.di != 0                 ? k.alongU
                                                            : k.alongV;
        EXPECT_EQ(s.slotStiffness(int(slot)), expected) << slot;
    }
    EXPECT_TRUE(familyModelled(s, Family::Structural));
    EXPECT_TRUE(familyModelled(s, Family::Shear));
    EXPECT_FALSE(familyModelled(s, Family::Bend));
    const auto springs = activeSprings<double>(s);
    ASSERT_EQ(springs.size(), 8u);
    for (const StencilSpring<double>& sp : springs)
        EXPECT_EQ(sp.stiffness, sp.dj == 0 && sp.di != 0   ? k.alongU
                                : sp.di == 0 && sp.dj != 0 ? k.alongV
                                                           : k.shear);
}

// Gershgorin on M⁻¹H: the free sheet's worst row over its own mass is a corner's,
// 2(K_u + K_v + K_s)/(ρ du dv/4), while H's own worst row is an interior vertex's,
// 2(2K_u + 2K_v + 4K_s); the damping rate is the material's.
TEST(MaterialModel, StabilityBoundIsTheWorstRowOverItsVertexMass) {
    const Scene s = fallingMaterialScene(Method::SymplecticEuler, 0.7);
    const Grid g = s.grid();
    const MembraneSprings k = membraneSprings(*s.material, g.du, g.dv);
    const double corner = s.material->density * g.du * g.dv / 4;
    const StabilityBound b = estimateStability(s, 40);
    EXPECT_NEAR(b.omega2Max, 2 * (k.alongU + k.alongV + k.shear) / corner, 1e-12 * b.omega2Max);
    EXPECT_NEAR(b.lambdaMax, 2 * (2 * k.alongU + 2 * k.alongV + 4 * k.shear), 1e-12 * b.lambdaMax);
    EXPECT_EQ(b.dampingRate, 0.7);
    EXPECT_GT(b.omega2Power, 0);
    EXPECT_LE(b.omega2Power, b.omega2Max);
    EXPECT_EQ(b.safeDt(Method::Verlet), methodDt(Method::Verlet, b.omega2Max, 0.7));
    EXPECT_DOUBLE_EQ(b.safeDt(Method::Verlet), 2 / std::sqrt(b.omega2Max));
}

// The per-vertex form is the special case m_k = m, c = μ/m: the same bound as λ and μ give.
TEST(MaterialModel, PerVertexFormBoundIsLambdaOverMass) {
    Scene s = materialScene(Method::SymplecticEuler);
    s.material.reset();
    s.cloth.mass = 0.25;
    s.springs = {200, 80, 20};
    s.damping = 3;
    const StabilityBound b = estimateStability(s, 40);
    EXPECT_DOUBLE_EQ(b.omega2Max, b.lambdaMax / 0.25);
    EXPECT_DOUBLE_EQ(b.dampingRate, 3 / 0.25);
    for (Method m : kMethods)
        EXPECT_DOUBLE_EQ(b.safeDt(m), methodDt(m, b.lambdaMax, 0.25, 3.0)) << methodName(m);
}

}  // namespace
}  // namespace cloth
