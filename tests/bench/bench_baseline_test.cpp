// The speed bench's 1x baseline (src/bench/bench_baseline.cpp) is timed beside the solvers, so it
// must simulate the same cloth: DESIGN.md §2's springs with rest length L = |di·du·û + dj·dv·v̂|,
// where û and v̂ need not be orthogonal. On a skewed cloth the shear diagonals (1, ±1) are the
// springs a "√(di²du² + dj²dv²)" rest length gets wrong; these tests load such a cloth.
#include "bench/bench_baseline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

constexpr long kSteps = 1000;

// û = x̂ and v̂ = (x̂ + ŷ)/√2 (the loader normalises [1, 1, 0]): 45° between the axes, every spring
// family, damping c = μ/m = 6 /s. Δt is inside the explicit Euler bound Δt < μ/λ_max with
// λ_max ≤ 2·4·(200 + 80 + 20) = 2400 N/m (Gershgorin, whatever the angle between the axes).
Scene skewedCloth(const std::string& gravity, const std::string& pins) {
    return parseScene(R"({
      "cloth": { "resolution": [9, 13], "size": [1.2, 1.7], "origin": [-0.6, 1.0, 0.2],
                 "u_axis": [1, 0, 0], "v_axis": [1, 1, 0], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": )" + gravity +
                          R"(,
      "pins": )" + pins + R"(,
      "integrator": { "method": "explicit_euler", "dt": 0.001 }
    })",
                      "skewed cloth (test)");
}

// Conservation of the rest state (DESIGN.md §2): with no gravity and no pins every spring of a
// cloth at its rest positions has |d| = L, so F = K(|d| − L)·d/|d| = 0 at every vertex, v stays 0
// and x stays at rest. What is left is rounding: |d| and L are each a few ulp from the exact
// length, a force of K·O(ε·L) that moves a vertex O(ε·L) over the run, far below 1e-12 of the
// extent. A wrong shear rest length (0.206 m instead of 0.270 m along (1, 1), 0.206 instead of
// 0.112 along (1, −1)) leaves forces of K·|ΔL| ≈ 5–8 N instead.
TEST(BenchBaseline, RestStateOfASkewedClothIsAnEquilibrium) {
    const Scene scene = skewedCloth("[0, 0, 0]", "[]");
    const Grid g = scene.grid();
    app::BaselineCloth baseline(scene);
    baseline.step(kSteps);
    double worst = 0;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i)
            worst = std::max(worst, glm::length(baseline.position(std::size_t(g.index(i, j))) -
                                                g.restPosition(i, j)));
    EXPECT_LT(worst / g.extent(), 1e-12)
        << "largest drift from rest after " << kSteps << " steps: " << worst << " m";
}

// Same scheme, same trajectory: the baseline is seed eq. (6), the CPU solver's explicit_euler
// is the same equation (DESIGN.md §2), so in double the two differ only by the order their
// sums are rounded in (the CPU solver gathers the springs in its own order). Tolerance: each step
// rounds x + Δt·v to within an ulp of |x| (≤ 3 m here) and the forces to a few ulp of K·|d|, a
// difference δ ≲ 4ε·|x| ≈ 2.7e-15 m a step. With Δt inside the damped bound every mode's
// amplification |1 + λΔt| is below 1, so the differences do not grow: at worst they add, N·δ ≈ 1e3
// · 2.7e-15 m = 2.7e-12 m, 1e-12 of the extent (2.69 m). That is the tolerance. A wrong shear rest
// length changes the hanging shape by decimetres.
TEST(BenchBaseline, TrajectoryMatchesTheCpuSolversExplicitEulerOnASkewedCloth) {
    const Scene scene = skewedCloth("[0.3, -9.81, -1.0]", "[[0, -1], [-1, -1]]");
    const Grid g = scene.grid();
    app::BaselineCloth baseline(scene);
    baseline.step(kSteps);
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Double, 1});
    const StepResult r = cpu->step(kSteps);
    ASSERT_FALSE(r.unstable) << r.reason;
    ASSERT_EQ(r.stepsTaken, kSteps);
    const SimState st = cpu->read();
    double gap = 0, travel = 0;
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            const std::size_t k = std::size_t(g.index(i, j));
            gap = std::max(gap, glm::length(baseline.position(k) - st.positions[k]));
            travel = std::max(travel, glm::length(st.positions[k] - g.restPosition(i, j)));
        }
    EXPECT_GT(travel / g.extent(), 1e-2) << "the cloth must move for the comparison to mean much";
    EXPECT_LT(gap / g.extent(), 1e-12)
        << "largest baseline − CPU solver gap after " << kSteps << " steps: " << gap << " m";
}

}  // namespace
}  // namespace cloth
