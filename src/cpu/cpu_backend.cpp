#include "cpu/cpu_backend.h"

#include <cstdio>

#include "cpu/cpu_memory.h"
#include "cpu/cpu_solver.h"
#include "model/errors.h"
#include "model/float_range.h"
#include "model/machine_memory.h"

namespace cloth {

std::unique_ptr<Solver> makeCpuSolver(const Scene& scene, const CpuOptions& options) {
    // The integrator's arrays, refused before any is allocated where they exceed the memory.
    const double vertices = double(scene.cloth.nu) * double(scene.cloth.nv);
    const double need =
                     vertices * double(cpuBytesPerVertex(
                                    options.precision, scene.integrator.method,
                                    scene.integrator.preconditioner, !scene.colliders.empty(), true,
                                    scene.anyFriction(), scene.integrator.vbdTranslates())),
                 have = physicalMemoryBytes();
    if (need > have) {
        char buf[240];
        std::snprintf(buf, sizeof buf,
                      "%d x %d vertices need about %.3g GB for %s in %s on the CPU, more than this "
                      "machine's %.3g GB of memory",
                      scene.cloth.nu, scene.cloth.nv, need / 1e9,
                      methodName(scene.integrator.method), precisionName(options.precision),
                      have / 1e9);
        throw InputError(scene.source, "cloth.resolution", buf);
    }
    if (options.precision == Precision::Float) {
        checkFloatRange(scene);
        return std::make_unique<CpuSolver<float>>(scene, options.threads, options.isa);
    }
    return std::make_unique<CpuSolver<double>>(scene, options.threads, options.isa);
}

}  // namespace cloth
