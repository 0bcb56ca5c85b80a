// A material on the grid (docs/physics.md "From a material to the grid"): the lumped masses add
// up to density × area with the sheet's centroid as centre of mass, and the springs give the
// lattice the material's membrane stiffness, measured here from the springs' own geometry (the
// energy of a homogeneous strain), not from the formulas that chose them.
#include <gtest/gtest.h>

#include <cmath>

#include "model/grid.h"
#include "model/material_presets.h"
#include "model/scene.h"

namespace cloth {
namespace {

Scene sheet(int nu, int nv, double sizeU, double sizeV, const Material& m) {
    Scene s;
    s.cloth.nu = nu;
    s.cloth.nv = nv;
    s.cloth.size = {sizeU, sizeV};
    s.cloth.origin = {0.3, 1.2, -0.4};
    s.material = m;
    return s;
}

Material fabric() {
    return {"", 0.15, 5000, 500, 5e-6, 0.1};
}

TEST(MaterialMass, TotalIsDensityTimesAreaAndTheCentreIsTheCentroid) {
    const Material m = fabric();
    for (auto [nu, nv] : {std::pair{2, 2}, {8, 8}, {17, 9}, {128, 128}, {33, 65}}) {
        const Scene s = sheet(nu, nv, 1.3, 0.7, m);
        const Grid g = s.grid();
        double total = 0;
        glm::dvec3 moment{0};
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) {
                total += s.vertexMass(i, j);
                moment += s.vertexMass(i, j) * g.restPosition(i, j);
            }
        const double area = 1.3 * 0.7;
        // Σ of nu·nv terms each rounded once: relative error below nu·nv·2⁻⁵³.
        const double tol = nu * nv * 1.2e-16;
        EXPECT_NEAR(total, m.density * area, tol * m.density * area) << nu << " x " << nv;
        EXPECT_NEAR(s.totalMass(), m.density * area, 1e-15);
        const glm::dvec3 centroid =
            g.restPosition(0, 0) + 0.5 * (g.restPosition(nu - 1, nv - 1) - g.restPosition(0, 0));
        const glm::dvec3 centre = moment / total;
        EXPECT_LT(glm::length(centre - centroid), 1e-12) << nu << " x " << nv;
    }
}

// Breaking the lumping (every vertex a full cell) moves the total by the boundary's half cells:
// the check above sees it.
TEST(MaterialMass, AFullCellAtTheBoundaryWouldBeSeen) {
    const Scene s = sheet(8, 8, 1, 1, fabric());
    const Grid g = s.grid();
    const double fullCells = 8 * 8 * s.material->density * g.du * g.dv;
    EXPECT_GT(std::abs(fullCells - s.totalMass()) / s.totalMass(), 0.2);
}

// The lattice's elastic constants from its springs: for a homogeneous small strain E (2 × 2, in
// the grid's (u, v) frame) a spring of rest vector L·n stretches by L·nᵀEn and stores
// ½K(L·nᵀEn)². Summed over the springs of one cell (one along u, one along v, both diagonals,
// each spring of an infinite lattice belonging to one cell) over the cell's area, W(E) is the
// energy density; its second derivatives are C₁₁, C₂₂, C₁₂ and 4·C₆₆.
struct Constants {
    double c11, c22, c12, c66;
};

Constants latticeConstants(const Scene& s) {
    const Grid g = s.grid();
    auto energy = [&](double e11, double e22, double e12) {
        double w = 0;
        for (int slot = 0; slot < 12; ++slot) {
            const SpringOffset& o = kSpringOffsets[std::size_t(slot)];
            // One of each ± pair per cell (a bend spring, two cells long, also one per vertex).
            if (o.di < 0 || (o.di == 0 && o.dj < 0)) continue;
            const double a = o.di * g.du, b = o.dj * g.dv;
            const double stretch =
                (a * a * e11 + b * b * e22 + 2 * a * b * e12) / std::sqrt(a * a + b * b);  // L·nᵀEn
            w += 0.5 * s.slotStiffness(slot) * stretch * stretch;
        }
        return w / (g.du * g.dv);
    };
    const double e = 1e-4;  // W is exactly quadratic: central differences are exact to rounding
    auto second = [&](auto f) { return (f(e) - 2 * f(0) + f(-e)) / (e * e); };
    Constants c;
    c.c11 = second([&](double x) { return energy(x, 0, 0); });
    c.c22 = second([&](double x) { return energy(0, x, 0); });
    const double c11PlusC22Plus2C12 = second([&](double x) { return energy(x, x, 0); });
    c.c12 = (c11PlusC22Plus2C12 - c.c11 - c.c22) / 2;
    c.c66 = second([&](double x) { return energy(0, 0, x); }) / 4;
    return c;
}

TEST(MaterialLattice, UniaxialStiffnessIsStretchAndShearStiffnessIsShear) {
    for (const Material& preset : materialPresets()) {
        for (auto [nu, nv, su, sv] : {std::tuple{8, 8, 1.0, 1.0},
                                      {64, 64, 1.0, 1.0},
                                      {33, 17, 1.0, 0.7},
                                      {9, 17, 0.5, 1.3}}) {
            const Scene s = sheet(nu, nv, su, sv, preset);
            const Constants c = latticeConstants(s);
            // Uniaxial tension along u with the sides free: σ₂₂ = 0 gives ε₂₂ = −(C₁₂/C₂₂)ε₁₁
            // and σ₁₁ = (C₁₁ − C₁₂²/C₂₂) ε₁₁.
            const double yu = c.c11 - c.c12 * c.c12 / c.c22, yv = c.c22 - c.c12 * c.c12 / c.c11;
            const std::string what =
                preset.preset + " on " + std::to_string(nu) + " x " + std::to_string(nv);
            EXPECT_NEAR(yu, preset.stretch, 1e-6 * preset.stretch) << what;
            EXPECT_NEAR(yv, preset.stretch, 1e-6 * preset.stretch) << what;
            EXPECT_NEAR(c.c66, preset.shear, 1e-6 * preset.shear) << what;
            // A central-force lattice obeys Cauchy's relation C₁₂ = C₆₆: its Poisson ratio is
            // G/C, not a free parameter (docs/physics.md).
            EXPECT_NEAR(c.c12, c.c66, 1e-6 * preset.shear) << what;
        }
    }
}

// The check has teeth: the springs of the seed's naive mapping K = stretch on every structural
// spring (shear's contribution to C₁₁ forgotten) miss the material's stretch.
TEST(MaterialLattice, ForgettingTheShearSpringsContributionWouldBeSeen) {
    Material m = fabric();
    Scene s = sheet(16, 16, 1, 1, m);
    s.material.reset();
    s.springs.structural = m.stretch;
    s.springs.shear = m.shear;
    const Constants c = latticeConstants(s);
    EXPECT_GT(std::abs(c.c11 - c.c12 * c.c12 / c.c22 - m.stretch) / m.stretch, 0.05);
}

TEST(MaterialPresets, EveryPresetIsPhysicalAndFoundByName) {
    EXPECT_EQ(materialPresets().size(), 6u);
    for (const Material& m : materialPresets()) {
        ASSERT_TRUE(materialPreset(m.preset)) << m.preset;
        EXPECT_GT(m.density, 0) << m.preset;
        EXPECT_GT(m.stretch, 0) << m.preset;
        EXPECT_GT(m.shear, 0) << m.preset;
        EXPECT_GT(m.bend, 0) << m.preset;
        EXPECT_GE(m.airDamping, 0) << m.preset;
        // docs/physics.md's linearised drag: c·ρ = 0.15 kg/(m²·s) for every preset.
        EXPECT_NEAR(m.airDamping * m.density, 0.15, 0.002) << m.preset;
    }
    EXPECT_FALSE(materialPreset("velvet"));
}

}  // namespace
}  // namespace cloth
