// implicit_euler's system A = m (1 + hc) I + h D + h² H (model/implicit_system.h): the block-
// Jacobi preconditioner inverts its 3×3 diagonal blocks, which must be A's own, term by term.
#include "model/implicit_system.h"

#include <gtest/gtest.h>

#include <random>

#include "support/draws.h"
#include "support/material_scene.h"

namespace cloth {
namespace {

// A_kk probed column by column: (A e_{k,d})_k for the three unit vectors at vertex k, against
// ImplicitSystem::diagonal(k), on a crumpled sheet with every term of A switched on (stretched
// and compressed springs, bending, spring damping, drag, the grab), at a corner, on the border
// and inside.
TEST(ImplicitSystem, DiagonalBlocksAreTheOperatorsOwn) {
    Scene scene = materialScene(Method::ImplicitEuler, 1.0 / 60);
    scene.material->bend = 2e-4;
    scene.material->springDamping = 3e-3;
    const Grid g = scene.grid();
    const std::vector<StencilSpring<double>> springs = activeSprings<double>(scene);
    std::vector<Vec3<double>> x;
    std::vector<double> inverseMass;
    std::mt19937 random(3);
    std::uniform_real_distribution<double> jitter(-0.3, 0.3);
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            x.push_back(g.restPosition(i, j) + g.du * test::drawVec3(jitter, random));
            inverseMass.push_back(1 / scene.vertexMass(i, j));
        }
    std::vector<std::uint8_t> pinned(std::size_t(g.count()), 0);
    pinned[0] = 1;
    ImplicitSystem<double, std::vector<Vec3<double>>> a;
    a.nu = g.nu;
    a.nv = g.nv;
    a.springs = &springs;
    a.bending = bendingWeights(g, scene.bendingStiffness());
    a.x = &x;
    a.inverseMass = inverseMass.data();
    a.pinned = pinned.data();
    a.h = scene.integrator.dt;
    a.drag = 1 + a.h * scene.dampingRate();
    a.springDamping = true;
    a.grabVertex = g.index(5, 6);
    a.grabStiffness = 40;
    ASSERT_TRUE(a.bending.active());
    for (const auto& [i, j] : {std::pair{g.nu - 1, 0}, {1, 0}, {0, 5}, {1, 1}, {5, 6}, {8, 4}}) {
        const std::int64_t k = g.index(i, j);
        const Sym3<double> block = a.diagonal(k);
        for (int d = 0; d < 3; ++d) {
            std::vector<Vec3<double>> e(x.size(), Vec3<double>(0)), column(x.size());
            e[std::size_t(k)][d] = 1;
            a.apply(e.data(), column.data(), 0, g.count());
            Vec3<double> unit(0);
            unit[d] = 1;
            const Vec3<double> expected = column[std::size_t(k)], got = block * unit;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[c], expected[c], 1e-12 * std::abs(block.xx))
                    << "(" << i << ", " << j << ") column " << d << " row " << c;
        }
        const Sym3<double> inverse = block.inverse();
        for (int d = 0; d < 3; ++d) {
            Vec3<double> unit(0);
            unit[d] = 1;
            const Vec3<double> back = inverse * (block * unit);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], c == d ? 1 : 0, 1e-12);
        }
    }
}

}  // namespace
}  // namespace cloth
