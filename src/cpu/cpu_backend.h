// The CPU backend as its callers see it (DESIGN.md §1): a Solver computing in float or double on
// worker threads, its row kernels compiled for each instruction set and picked at construction.
#pragma once

#include <memory>

#include "cpu/cpu_rows.h"
#include "solver/solver.h"

namespace cloth {

struct CpuOptions {
    Precision precision = Precision::Double;
    int threads = 0;            // 0: one per hardware thread, 1: serial
    CpuIsa isa = CpuIsa::Auto;  // row kernels; Auto: the widest this CPU has (cpu/cpu_rows.h)
};

std::unique_ptr<Solver> makeCpuSolver(const Scene& scene, const CpuOptions& options = {});

}  // namespace cloth
