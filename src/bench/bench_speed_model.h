// What `clothsim bench speed` decides without running anything, kept header-only so that the
// tests check it in-process: the Debug refusal, the bytes a step must move, the bytes each
// backend allocates per vertex, and whether a size fits in memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "cpu/cpu_memory.h"
#include "model/scene.h"
#include "solver/solver.h"

namespace cloth::app {

// Timings of an unoptimised build mean nothing: refused unless --allow-debug.
inline std::optional<std::string> debugRefusal(const std::string& buildType, bool allowDebug) {
    if (allowDebug || (buildType != "Debug" && buildType != "debug")) return std::nullopt;
    return "this clothsim is a " + buildType +
           " build, whose timings mean nothing; build with -DCMAKE_BUILD_TYPE=Release, or pass "
           "--allow-debug";
}

// The traffic model (bytes a step must move at least, per vertex): whatever the integrator, one
// step reads each vertex's position and velocity and writes both back, 4 vectors of the
// backend's storage. Forces, normals and the integrator's own stages are left out: they can stay
// in cache or registers, so this is a lower bound and achieved GB/s a lower bound on the
// traffic. CPU: 4 vec3 of float (48 B) or double (96 B); GPU: 4 std430 vec4 of float (64 B);
// the baseline: 4 vec3 of double (96 B).
inline std::size_t minStepBytesPerVertex(Backend backend, Precision precision) {
    if (backend == Backend::Gpu) return 4 * 4 * sizeof(float);
    return 4 * 3 * (precision == Precision::Double ? sizeof(double) : sizeof(float));
}
inline constexpr const char* kTrafficModel =
    "min bytes per vertex-step = read x and v + write x and v = 4 vectors (cpu: 3 scalars of the "
    "precision; gpu: std430 vec4 of float; baseline: 3 doubles); forces and stages not counted";

using cloth::cpuBytesPerVertex;  // (cpu/cpu_memory.h)

// The baseline (bench_baseline.h): x, v and their next values, 4 vec3 of double.
inline constexpr std::size_t kBaselineBytesPerVertex = 4 * 3 * sizeof(double);

// A size is refused when the largest of its runs would not fit in `availableBytes`: the most
// any backend allocates per vertex (taken as 320 B, over the CPU's 305 B for block-Jacobi implicit
// Euler in double with colliders, the GPU's vec4 buffers and the baseline's 96 B) times the
// vertex count.
inline constexpr std::size_t kWorstBytesPerVertex = 320;
inline std::optional<std::string> sizeRefusal(std::int64_t side, std::uint64_t availableBytes) {
    const std::uint64_t need = std::uint64_t(side) * std::uint64_t(side) * kWorstBytesPerVertex;
    if (need <= availableBytes) return std::nullopt;
    return "size " + std::to_string(side) + " needs about " + std::to_string(need >> 20) +
           " MiB, more than the " + std::to_string(availableBytes >> 20) + " MiB available";
}

}  // namespace cloth::app
