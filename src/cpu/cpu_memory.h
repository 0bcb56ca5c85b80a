// What the CPU solver allocates per vertex, as a model that needs no solver: bench speed reports
// it as the CPU's memory, and makeCpuSolver refuses a grid whose arrays would not fit in the
// machine's memory before allocating any (tests/cpu/cpu_simd_test.cpp holds it to
// CpuSolver::allocatedBytes for every integrator and precision).
#pragma once

#include <cstddef>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// What the CPU solver allocates per vertex (cpu/cpu_solver.h, CpuSolver::allocatedBytes): the
// positions, velocities and pin positions (3 vec3 in structure-of-arrays) plus either a second
// position buffer (explicit and symplectic Euler: the fused sweep writes the new positions there
// and keeps no forces) or the forces (the other integrators), and the pinned flag (1 byte); rk4
// adds x0, v0, ΣX, ΣV and implicit Euler its CG vectors dv, r, p, Ap (4 vec3 each; with the
// block-Jacobi preconditioner z and the inverted diagonal block, a vec3 and 6 scalars; with
// colliders its contacts in the solve, 12 scalars: n, z, hold, b, grip and two flags padded),
// vbd the step's displacement, the inertial target's and the previous velocity (Chebyshev's two
// iterates and, with a material's bending, its Hessian diagonal, one scalar, are not counted),
// and the inverse mass 1/m_k (one scalar per vertex), where a collider has friction its contacts
// (n, h v_c, c_f λ: 7 scalars), with colliders and translation sweeps the last pushes (3); with
// row kernels vbd keeps the copy its kernel reads
// (cpu/cpu_vbd_phases.h: x, d, ŷ, 1/m and the pin flag); the threads' scratch rows are O(side), not
// counted, nor is the multigrid preconditioner's hierarchy.
inline std::size_t cpuBytesPerVertex(Precision precision, Method method,
                                     Preconditioner preconditioner = Preconditioner::Jacobi,
                                     bool colliders = false, bool rowKernels = true,
                                     bool friction = false, bool translation = false) {
    const std::size_t scalar = precision == Precision::Double ? sizeof(double) : sizeof(float);
    std::size_t vectors = 4;
    if (method == Method::Rk4 || method == Method::ImplicitEuler) vectors += 4;
    if (method == Method::Vbd) vectors += 2;  // d, ŷ, v_{n−1} in place of the forces
    std::size_t scalars = vectors * 3 + 1;
    if (method == Method::ImplicitEuler && preconditioner == Preconditioner::Jacobi) scalars += 9;
    if (method == Method::ImplicitEuler && colliders) scalars += 12;
    if (method == Method::Vbd && friction) scalars += 7;
    if (method == Method::Vbd && colliders && translation) scalars += 3;
    const bool phases = method == Method::Vbd && rowKernels;
    if (phases) scalars += 3 * 3 + 1;
    return scalars * scalar + (phases ? 2 : 1);
}

}  // namespace cloth
