// Runs of implicit Euler with one preconditioner on the CPU backend, and how far two end states
// lie apart: the preconditioner tests (block-Jacobi, multigrid) compare solves with them.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "backends/solver_factory.h"

namespace cloth::test {

struct Solved {
    SimState state;
    SolveStats stats;
};

inline Solved runPreconditioned(Scene scene, Preconditioner p, Precision precision, int threads,
                                long steps) {
    scene.integrator.preconditioner = p;
    std::unique_ptr<Solver> solver = makeSolver(scene, {Backend::Cpu, precision, threads});
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << r.reason;
    return {solver->read(), solver->solveStats()};
}

// max_k |x_a,k − x_b,k| [m]
inline double largestDifference(const SimState& a, const SimState& b) {
    double d = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k)
        d = std::max(d, glm::length(a.positions[k] - b.positions[k]));
    return d;
}

}  // namespace cloth::test
