// The CPU backend's paths compared bit for bit (the scalar oracle against the row kernels of each
// instruction set and thread count): a run of CpuSolver<T> and a bitwise comparison of states.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "cpu/cpu_solver.h"

namespace cloth::test {

// `steps` steps of `scene` on CpuSolver<T> with `isa` and `threads`, from `start` when given
// (else the scene's rest state); an unstable run fails the test.
template <typename T>
SimState runCpu(const Scene& scene, CpuIsa isa, int threads, long steps,
                const SimState* start = nullptr) {
    CpuSolver<T> solver(scene, threads, isa);
    if (start) solver.write(*start);
    const StepResult r = solver.step(steps);
    EXPECT_FALSE(r.unstable) << r.reason;
    return solver.read();
}

// Bitwise: the doubles read back are exact conversions of T, so equal bits here are equal bits
// in the solver.
inline void expectSameBits(const SimState& a, const SimState& b, const std::string& what) {
    ASSERT_EQ(a.positions.size(), b.positions.size());
    EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(),
                             a.positions.size() * sizeof(glm::dvec3)))
        << what << ": positions differ";
    EXPECT_EQ(0, std::memcmp(a.velocities.data(), b.velocities.data(),
                             a.velocities.size() * sizeof(glm::dvec3)))
        << what << ": velocities differ";
}

}  // namespace cloth::test
