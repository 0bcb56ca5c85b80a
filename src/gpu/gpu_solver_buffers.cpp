#include <GL/glew.h>

#include <vector>

#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"

// The integrators' own buffers (docs/integrators.md): which ones each method and
// preconditioner binds, and their sizes.

namespace cloth {
namespace {

using gpu::bufferData;
using gpu::kVec4;

// The buffers of docs/integrators.md's stage or solver state, beyond the core eight.
// `contacts`: the scene has colliders (implicit_euler's contacts in the solve).
std::vector<gpu::Binding> integratorBindings(Method m, Preconditioner p, bool contacts) {
    if (m == Method::ImplicitEuler && contacts) {
        std::vector<gpu::Binding> bindings = integratorBindings(m, p, false);
        bindings.push_back(gpu::kCgContacts);
        return bindings;
    }
    if (m == Method::ImplicitEuler && p == Preconditioner::Jacobi)
        return {gpu::kCgVelocityChange, gpu::kCgResidual, gpu::kCgDirection, gpu::kCgProduct,
                gpu::kCgPartials,       gpu::kCgState,    gpu::kCgInverse};
    switch (m) {
        case Method::Rk4:
            return {gpu::kRk4StartPositions, gpu::kRk4StartVelocities, gpu::kRk4SumPositions,
                    gpu::kRk4SumVelocities};
        case Method::ImplicitEuler:
            return {gpu::kCgVelocityChange, gpu::kCgResidual, gpu::kCgDirection,
                    gpu::kCgProduct,        gpu::kCgPartials, gpu::kCgState};
        case Method::Vbd:
            return {gpu::kVbdStart, gpu::kVbdInertial, gpu::kVbdPrevious, gpu::kVbdBefore,
                    gpu::kVbdBeforeLast};
        default:
            return {};
    }
}

}  // namespace

void GpuSolver::generateIntegratorBuffers() {
    for (gpu::Binding b : integratorBindings(method_, preconditioner_, !scene_.colliders.empty()))
        glGenBuffers(1, &buffers_[b]);
}

// Stage or solver state, as zeros: written by the step before it is read. The bindings from 8 on
// are each integrator's own, so one number names different buffers (kCgPartials is
// kVbdBeforeLast): a size is chosen by the method and the binding together.
void GpuSolver::allocateIntegratorBuffers() {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const bool cg = method_ == Method::ImplicitEuler;
    for (gpu::Binding b : integratorBindings(method_, preconditioner_, !scene_.colliders.empty())) {
        if (cg && b == gpu::kCgPartials) {
            // Two floats per work group, rounded up to whole vec4s.
            const std::size_t groups = std::size_t(groupsX_) * std::size_t(groupsY_);
            bufferData(buffers_[b], nullptr, (2 * groups + 3) / 4 * kVec4);
        } else if (cg && b == gpu::kCgInverse) {
            bufferData(buffers_[b], nullptr, 2 * n * kVec4);
        } else if (cg && b == gpu::kCgVelocityChange) {  // the warm start's first guess: 0
            bufferData(buffers_[b], std::vector<glm::vec4>(n, glm::vec4(0)));
        } else if (cg && b == gpu::kCgState) {
            const gpu::CgState zero{};
            bufferData(buffers_[b], &zero, sizeof zero);
        } else {
            bufferData(buffers_[b], nullptr, n * kVec4);
        }
    }
}

}  // namespace cloth
