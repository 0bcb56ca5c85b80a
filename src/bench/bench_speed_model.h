// What `clothsim bench speed` decides without running anything, kept header-only so that the
// tests check it in-process: the Debug refusal, the bytes a step must move, the bytes each
// backend allocates per vertex, and whether a size fits in memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

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

// What the CPU solver allocates per vertex (cpu/cpu_solver.h, CpuSolver::allocatedBytes): the
// positions, velocities and pin positions (3 vec3 in structure-of-arrays) plus either a second
// position buffer (explicit and symplectic Euler: the fused sweep writes the new positions there
// and keeps no forces) or the forces (the other integrators), and the pinned flag (1 byte); rk4
// adds x0, v0, ΣX, ΣV and implicit Euler its CG vectors dv, r, p, Ap (4 vec3 each; with the
// block-Jacobi preconditioner z and the inverted diagonal block, a vec3 and 6 scalars; with
// colliders its contacts in the solve, 12 scalars: n, z, hold, b, grip and two flags padded),
// vbd the
// step's start, the inertial target and the previous velocity (Chebyshev's two iterates and,
// with a material's bending, its Hessian diagonal, one scalar, are not counted), and the
// inverse mass 1/m_k (one scalar per vertex); with row kernels vbd keeps the copy its kernel
// reads (cpu/cpu_vbd_phases.h: x, x_n, y, 1/m and the pin flag); the threads' scratch rows are
// O(side), not counted.
inline std::size_t cpuBytesPerVertex(Precision precision, Method method,
                                     Preconditioner preconditioner = Preconditioner::Jacobi,
                                     bool colliders = false, bool rowKernels = true) {
    const std::size_t scalar = precision == Precision::Double ? sizeof(double) : sizeof(float);
    std::size_t vectors = 4;
    if (method == Method::Rk4 || method == Method::ImplicitEuler) vectors += 4;
    if (method == Method::Vbd) vectors += 2;  // x_n, y, v_{n−1} in place of the forces
    std::size_t scalars = vectors * 3 + 1;
    if (method == Method::ImplicitEuler && preconditioner == Preconditioner::Jacobi) scalars += 9;
    if (method == Method::ImplicitEuler && colliders) scalars += 12;
    const bool phases = method == Method::Vbd && rowKernels;
    if (phases) scalars += 3 * 3 + 1;
    return scalars * scalar + (phases ? 2 : 1);
}

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
