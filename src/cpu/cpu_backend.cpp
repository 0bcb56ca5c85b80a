#include "cpu/cpu_backend.h"

#include "cpu/cpu_solver.h"

namespace cloth {

std::unique_ptr<Solver> makeCpuSolver(const Scene& scene, const CpuOptions& options) {
    if (options.precision == Precision::Float)
        return std::make_unique<CpuSolver<float>>(scene, options.threads, options.isa);
    return std::make_unique<CpuSolver<double>>(scene, options.threads, options.isa);
}

}  // namespace cloth
