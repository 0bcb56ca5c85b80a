// The aggregation multigrid (cpu/cpu_aggregation.h) as an operator on the drape's stiff system:
// its coarse spaces carry its candidates, its coarse grids are Galerkin products, and its cycle
// is the symmetric positive definite contraction the conjugate gradient needs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "cpu/cpu_aggregation.h"
#include "scene/scene_loader.h"
#include "support/material_scene.h"
#include "support/multigrid_fixture.h"
#include "support/preconditioned_runs.h"
#include "support/same_bits.h"
#include "support/sanitized.h"

namespace cloth {
using test::Fixture;
using test::Solved;
struct Hierarchy {
    Fixture f;
    Aggregation aggregation;
    explicit Hierarchy(int cells, Aggregation::Settings settings = {}) : f(cells, 1e6) {
        aggregation.setSettings(settings);
        aggregation.setup(fineGrid(), positions());
    }
    // The fixture's system as of its last linearise, and its positions, 3 a vertex.
    BlockGrid fineGrid() const {
        BlockGrid fine;
        f.multigrid.fineGrid(fine);
        return fine;
    }
    std::vector<double> positions() const {
        std::vector<double> x;
        for (std::int64_t k = 0; k < f.grid.count(); ++k)
            for (int d = 0; d < 3; ++d) x.push_back(f.x.get(k)[d]);
        return x;
    }
    std::vector<double> random(int l, unsigned seed) const {
        const BlockGrid& g = aggregation.grid(l);
        std::mt19937 random(seed);
        std::normal_distribution<double> normal;
        std::vector<double> v(g.dofs());
        for (std::size_t e = 0; e < v.size(); ++e) v[e] = g.fixed[e] ? 0 : normal(random);
        return v;
    }
    std::vector<double> cycle(const std::vector<double>& r) {
        std::vector<double> z(r.size());
        aggregation.apply(r.data(), z.data());
        return z;
    }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
    double s = 0;
    for (std::size_t e = 0; e < a.size(); ++e) s += a[e] * b[e];
    return s;
}

namespace {
// The fine grid handed over is implicit Euler's matrix A: its product is the system's.
TEST(Aggregation, FineGridIsTheSystemsMatrix) {
    Hierarchy h(24);
    const auto p = h.f.random(5);
    const auto expected = h.f.product(p);
    std::vector<double> flat, got(3 * p.size());
    for (const auto& v : p)
        for (int d = 0; d < 3; ++d) flat.push_back(v[d]);
    h.aggregation.grid(0).apply(flat.data(), got.data());
    double worst = 0, scale = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
        if (h.f.pinned[k]) continue;
        for (int d = 0; d < 3; ++d) {
            worst = std::max(worst, std::abs(got[3 * k + std::size_t(d)] - expected[k][d]));
            scale = std::max(scale, std::abs(expected[k][d]));
        }
    }
    EXPECT_LT(worst, 1e-12 * scale);
}

// Smoothed aggregation's premise: the tentative P reproduces every candidate exactly, level by
// level (B_l = P_t B_{l+1} on every free unknown).
TEST(Aggregation, TentativeProlongationCarriesEveryCandidate) {
    Aggregation::Settings settings;
    settings.smooth = false;
    Hierarchy h(48, settings);
    ASSERT_GE(h.aggregation.levels(), 3);
    for (int l = 0; l + 1 < h.aggregation.levels(); ++l) {
        const BlockGrid& fine = h.aggregation.grid(l);
        const BlockGrid& coarse = h.aggregation.grid(l + 1);
        const std::size_t n = fine.dofs(), nc = coarse.dofs();
        // A coarse grid that is coarsened again relaxed its adaptive candidates after this P
        // was built: only the rigid ones are still P's preimages of the grid above's there.
        const bool relaxed = l + 2 < h.aggregation.levels();
        const int columns = relaxed ? Aggregation::kRigid : h.aggregation.candidateCount(l);
        for (int c = 0; c < columns; ++c) {
            std::vector<double> got(n, 0.0);
            h.aggregation.prolong(l, &h.aggregation.candidates(l + 1)[std::size_t(c) * nc],
                                  got.data());
            double worst = 0, scale = 0;
            for (std::size_t e = 0; e < n; ++e) {
                const double want = h.aggregation.candidates(l)[std::size_t(c) * n + e];
                worst = std::max(worst, std::abs(got[e] - want));
                scale = std::max(scale, std::abs(want));
            }
            EXPECT_LT(worst, 1e-10 * scale) << "level " << l << ", candidate " << c;
        }
    }
}

// Every coarse grid is Pᵀ A P: A_c w = Pᵀ (A (P w)) for any w.
TEST(Aggregation, CoarseGridsAreGalerkinProducts) {
    Hierarchy h(48);
    for (int l = 0; l + 1 < h.aggregation.levels(); ++l) {
        const BlockGrid& fine = h.aggregation.grid(l);
        const BlockGrid& coarse = h.aggregation.grid(l + 1);
        const auto w = h.random(l + 1, 9);
        std::vector<double> pw(fine.dofs(), 0.0), apw(fine.dofs()), expected(coarse.dofs()),
            got(coarse.dofs());
        h.aggregation.prolong(l, w.data(), pw.data());
        fine.apply(pw.data(), apw.data());
        h.aggregation.restrict(l, apw.data(), expected.data());
        coarse.apply(w.data(), got.data());
        double worst = 0, scale = 0;
        for (std::size_t e = 0; e < got.size(); ++e) {
            if (coarse.fixed[e]) continue;
            worst = std::max(worst, std::abs(got[e] - expected[e]));
            scale = std::max(scale, std::abs(expected[e]));
        }
        EXPECT_LT(worst, 1e-9 * scale) << "level " << l + 1;
    }
}

// The CG's preconditioner must be symmetric, u·V w = w·V u, and positive definite, u·V u > 0.
TEST(Aggregation, VCycleIsSymmetricPositiveDefinite) {
    Hierarchy h(48);
    const auto u = h.random(0, 1), w = h.random(0, 2);
    const double uvw = dot(u, h.cycle(w)), wvu = dot(w, h.cycle(u));
    EXPECT_NEAR(uvw, wvu, 1e-9 * std::abs(uvw));
    for (unsigned seed = 3; seed <= 6; ++seed) {
        const auto v = h.random(0, seed);
        EXPECT_GT(dot(v, h.cycle(v)), 0) << "seed " << seed;
    }
}

// Conjugate gradient iterations to a relative residual of 1e-6 from 0, preconditioned by the
// hierarchy's V-cycle.
int iterationsToSolve(const BlockGrid& a, const std::vector<double>& b, Aggregation& v) {
    const std::size_t n = b.size();
    std::vector<double> r = b, z(n), p(n), ap(n);
    const double bb = dot(b, b);
    v.apply(r.data(), z.data());
    p = z;
    double rz = dot(r, z);
    for (int it = 1; it <= 500; ++it) {
        a.apply(p.data(), ap.data());
        const double alpha = rz / dot(p, ap);
        for (std::size_t e = 0; e < n; ++e) r[e] -= alpha * ap[e];
        if (dot(r, r) <= 1e-12 * bb) return it;
        v.apply(r.data(), z.data());
        const double next = dot(r, z);
        for (std::size_t e = 0; e < n; ++e) p[e] = z[e] + next / rz * p[e];
        rz = next;
    }
    return 501;
}

// Each grid's coarse space is built from that grid's candidates, so they must be near-null
// there: the adaptive ones are relaxed again on every coarse grid. A four-grid cycle then
// preconditions as well as three grids with the third solved exactly; relaxed on the first
// coarse grid only, the flat sheet at 96² took 13 iterations against 4.
TEST(Aggregation, DeeperGridsKeepTheCyclesStrength) {
    Hierarchy h(96);
    for (int j = 0; j < h.f.grid.nv; ++j)  // the flat sheet at rest
        for (int i = 0; i < h.f.grid.nu; ++i)
            h.f.x.set(h.f.grid.index(i, j), h.f.grid.restPosition(i, j));
    h.f.multigrid.linearise(h.f.system, CycleThreads{});
    const BlockGrid fine = h.fineGrid();
    const std::vector<double> x = h.positions();
    const std::vector<double> b = h.random(0, 4);
    int counts[2] = {0, 0};
    for (int levels : {3, 4}) {
        Aggregation::Settings settings;
        settings.maxLevels = levels;
        settings.coarsestDofs = 1;  // three grids: the third (11² × 14 unknowns) solved exactly
        Aggregation v;
        v.setSettings(settings);
        v.setup(fine, x);
        ASSERT_EQ(v.levels(), levels);
        counts[levels - 3] = iterationsToSolve(fine, b, v);
    }
    std::printf("flat 96², stretch 1e6: %d iterations with three grids, %d with four\n", counts[0],
                counts[1]);
    EXPECT_LE(counts[1], counts[0] + 2);
}

// The candidates are carried from one setup to the next and relaxed again, so the relaxation
// accumulates while the sheet changes slowly (a subspace iteration of the smoother): set up
// three times at one state, the cycle needs fewer iterations than after the first setup.
TEST(Aggregation, CarriedCandidatesImproveFromSetupToSetup) {
    Hierarchy h(96);
    const BlockGrid fine = h.fineGrid();
    const std::vector<double> x = h.positions();
    const std::vector<double> b = h.random(0, 4);
    Aggregation v;
    int counts[3];
    for (int& count : counts) {
        v.setup(fine, x);
        count = iterationsToSolve(fine, b, v);
    }
    std::printf("sagged 96², stretch 1e6: %d, %d, %d iterations after 1, 2, 3 setups\n", counts[0],
                counts[1], counts[2]);
    EXPECT_LT(counts[2], counts[0]);
}

// A preconditioner changes how the system is solved, never which: the material sheet (pinned
// corners, wind, drag, bending, spring damping) at Δt = 1/60 solved to 1e-11 moves the same with
// the aggregation's V-cycle as with the geometric one, in float and double.
TEST(AggregationSolver, SolvesTheSameSystemAsTheGeometricMultigrid) {
    Scene scene = materialScene(Method::ImplicitEuler, 1.0 / 60);
    scene.material->bend = 1e-4;
    scene.material->springDamping = 1e-3;
    scene.integrator.tolerance = 1e-11;
    scene.integrator.maxIterations = 2000;
    const Solved multigrid =
        test::runPreconditioned(scene, Preconditioner::Multigrid, Precision::Double, 1, 60);
    const Solved aggregation =
        test::runPreconditioned(scene, Preconditioner::Aggregation, Precision::Double, 2, 60);
    EXPECT_EQ(aggregation.stats.misses, 0);
    const double d = test::largestDifference(multigrid.state, aggregation.state);
    std::printf(
        "after 1 s: |x_multigrid − x_aggregation| ≤ %.3g m; iterations per step %.1f → "
        "%.1f\n",
        d, double(multigrid.stats.iterations) / multigrid.stats.solves,
        double(aggregation.stats.iterations) / aggregation.stats.solves);
    EXPECT_LT(d, 1e-9 * scene.grid().extent());
    scene.integrator.tolerance = 1e-5;  // what float can reach
    const Solved single =
        test::runPreconditioned(scene, Preconditioner::Aggregation, Precision::Float, 2, 60);
    EXPECT_EQ(single.stats.misses, 0);
    EXPECT_LT(test::largestDifference(multigrid.state, single.state), 1e-4 * scene.grid().extent());
}

// The point of building the coarse spaces from the system: the stiff hanging sheet (stretch
// 1e6 N/m, Δt = 1/60, relative residual 1e-6) folds into near-isometric modes that the geometric
// V-cycle's interpolation cannot carry, and its count grows step by step; the aggregation's does
// not. 64², the first 20 steps, in double.
TEST(AggregationSolver, StiffHangingSheetTakesFewerIterations) {
    const Scene scene = loadScene(
        CLOTH_SOURCE_DIR "/scenes/hanging.json",
        {"cloth.resolution=[64,64]", "material.stretch=1e6", "integrator.method=\"implicit_euler\"",
         "integrator.dt=0.016667", "integrator.tolerance=1e-6", "integrator.max_iterations=3000"});
    const long steps = test::sanitizedSteps(20, 4);
    const Solved geometric =
        test::runPreconditioned(scene, Preconditioner::Multigrid, Precision::Double, 2, steps);
    const Solved aggregation =
        test::runPreconditioned(scene, Preconditioner::Aggregation, Precision::Double, 2, steps);
    std::printf(
        "hanging 64², stretch 1e6, %ld steps: multigrid %.1f a step (most %d), "
        "aggregation %.1f (most %d)\n",
        steps, double(geometric.stats.iterations) / double(steps), geometric.stats.mostIterations,
        double(aggregation.stats.iterations) / double(steps), aggregation.stats.mostIterations);
    EXPECT_EQ(aggregation.stats.misses, 0);
    EXPECT_LT(aggregation.stats.mostIterations, geometric.stats.mostIterations);
    EXPECT_LE(aggregation.stats.mostIterations, 20);
}

// The CG's bands meet the one-thread V-cycle at barriers: any team gives the same bits.
TEST(AggregationSolver, RunsAreBitIdenticalOnAnyThreadCount) {
    Scene scene = materialScene(Method::ImplicitEuler, 1.0 / 60);
    scene.cloth.nu = 40;
    scene.cloth.nv = 45;
    scene.pins = {{0, 44}, {39, 44}};
    for (Precision precision : {Precision::Float, Precision::Double}) {
        const Solved serial =
            test::runPreconditioned(scene, Preconditioner::Aggregation, precision, 1, 5);
        const Solved parallel =
            test::runPreconditioned(scene, Preconditioner::Aggregation, precision, 3, 5);
        test::expectSameBits(serial.state, parallel.state, "3 threads");
        EXPECT_EQ(serial.stats.iterations, parallel.stats.iterations);
    }
}

}  // namespace
}  // namespace cloth
