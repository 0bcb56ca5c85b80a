// The CPU backend with a material's bending energy (model/bending.h, docs/physics.md "Bending"):
// the row kernels give the vertex-by-vertex path's bits; the solver matches the reference, which
// writes the energy's force as a scatter over stencils rather than a gather; implicit Euler's
// system includes the bending Hessian; the reported energy includes the bending energy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "cpu/cpu_backend.h"
#include "cpu/cpu_solver.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "support/material_scene.h"
#include "support/reference_bridge.h"
#include "support/same_bits.h"

namespace cloth {
namespace {

using test::expectSameBits;
using test::runCpu;

// The material sheet of support/material_scene.h with a bending stiffness that matters: on
// 0.08 × 0.06 m cells B = 1e-3 N·m gives w ≈ B/h² ≈ 0.2–0.3 N/m against springs of ~5e3 N/m,
// and the sheet, hanging from two corners, bends visibly within the run.
Scene bendingScene(Method method, double bend = 1e-3) {
    Scene s = materialScene(method, 1e-4);
    s.material->bend = bend;
    s.integrator.tolerance = 1e-12;
    s.integrator.maxIterations = 1000;
    return s;
}

TEST(BendingSolver, EveryInstructionSetAndThreadCountGivesTheScalarPathsBits) {
    for (Method method : {Method::SymplecticEuler, Method::Verlet, Method::ImplicitEuler}) {
        const Scene scene = bendingScene(method);
        const SimState scalarF = runCpu<float>(scene, CpuIsa::Scalar, 1, 60);
        const SimState scalarD = runCpu<double>(scene, CpuIsa::Scalar, 1, 60);
        for (CpuIsa isa : {CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512}) {
            if (!cpuIsaSupported(isa)) continue;
            for (int threads : {1, 3}) {
                const std::string what = std::string(methodName(method)) + " " + cpuIsaName(isa) +
                                         " " + std::to_string(threads) + " threads";
                expectSameBits(runCpu<float>(scene, isa, threads, 60), scalarF, what + " float");
                expectSameBits(runCpu<double>(scene, isa, threads, 60), scalarD, what + " double");
            }
        }
    }
}

double maxDeviation(const SimState& s, const ref::Simulation& r, double extent) {
    return maxDeviationOverExtent(s, r, extent);
}

// Against the reference in double: the same tolerances as the material sheet without bending
// (tests/cpu/material_test.cpp): rounding only, 1e-12 of the extent; implicit Euler's two CGs
// stop at |r| ≤ 1e-12|b|, 1e-9. The bending must also have moved the sheet: without it the
// reference ends more than 100× the tolerance away.
TEST(BendingSolver, TheCpuSolverMatchesTheReferenceWithBending) {
    for (Method method :
         {Method::SymplecticEuler, Method::Verlet, Method::Rk4, Method::ImplicitEuler}) {
        const Scene scene = bendingScene(method);
        const double extent = scene.grid().extent();
        const long steps = 1000;
        std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 2});
        ASSERT_FALSE(solver->step(steps).unstable);
        ref::Simulation sim(toReference(scene));
        Scene flat = scene;
        flat.material->bend = 0;
        ref::Simulation noBending(toReference(flat));
        for (long n = 0; n < steps; ++n) {
            sim.step();
            noBending.step();
        }
        const double tolerance = method == Method::ImplicitEuler ? 1e-9 : 1e-12;
        const double off = maxDeviation(solver->read(), sim, extent);
        const double bendingEffect = maxDeviation(solver->read(), noBending, extent);
        std::printf("%-16s: %.3g off the reference, bending moved it %.3g\n", methodName(method),
                    off, bendingEffect);
        EXPECT_LT(off, tolerance) << methodName(method);
        EXPECT_GT(bendingEffect, 100 * tolerance) << methodName(method);
    }
}

// The energy the diagnostics report includes the bending energy (the reference's, a quadratic
// form evaluated its own way) at a bent state.
TEST(BendingSolver, TheReportedEnergyIncludesTheBendingEnergy) {
    const Scene scene = bendingScene(Method::SymplecticEuler);
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Double, 1});
    ASSERT_FALSE(solver->step(500).unstable);
    const SimState state = solver->read();
    ref::Simulation sim(toReference(scene));
    sim.setState(toReferenceVectors(state.positions), toReferenceVectors(state.velocities));
    const Energy e = energy(scene, state);
    EXPECT_GT(e.bending, 0);
    EXPECT_NEAR(e.bending, sim.bendingEnergy(), 1e-9 * sim.bendingEnergy());
}

}  // namespace
}  // namespace cloth
