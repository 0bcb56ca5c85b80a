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

// What a buffer holds, which sets its size. The bindings from 8 on are each integrator's own, so
// one number names different buffers (kCgPartials is kVbdBeforeLast): the size goes with the
// binding in the integrator's list, never from the number alone.
enum class Contents {
    PerVertex,       // one vec4 per vertex, zeros
    TwoPerVertex,    // two vec4 per vertex (the block-Jacobi inverses, vbd's contacts)
    ThreePerVertex,  // three vec4 per vertex (the contacts in the solve)
    Partials,        // two floats per work group of the grid dispatch, in whole vec4s
    Translation,     // one vec4, then three per work group of the grid dispatch
    CgState,         // one gpu::CgState
};
struct IntegratorBuffer {
    gpu::Binding binding;
    Contents contents = Contents::PerVertex;
};

// The buffers of docs/integrators.md's stage or solver state, beyond the core eight.
// `contacts`: the scene has colliders (implicit_euler's contacts in the solve, vbd's contacts).
std::vector<IntegratorBuffer> integratorBuffers(Method m, Preconditioner p, bool contacts) {
    switch (m) {
        case Method::Rk4:
            return {{gpu::kRk4StartPositions},
                    {gpu::kRk4StartVelocities},
                    {gpu::kRk4SumPositions},
                    {gpu::kRk4SumVelocities}};
        case Method::ImplicitEuler: {
            std::vector<IntegratorBuffer> cg = {{gpu::kCgVelocityChange},  // first guess: 0
                                                {gpu::kCgResidual},
                                                {gpu::kCgDirection},
                                                {gpu::kCgProduct},
                                                {gpu::kCgPartials, Contents::Partials},
                                                {gpu::kCgState, Contents::CgState}};
            if (p == Preconditioner::Jacobi)
                cg.push_back({gpu::kCgInverse, Contents::TwoPerVertex});
            if (contacts) cg.push_back({gpu::kCgContacts, Contents::ThreePerVertex});
            return cg;
        }
        case Method::Vbd: {
            std::vector<IntegratorBuffer> vbd = {
                {gpu::kVbdDisplacement}, {gpu::kVbdInertial},
                {gpu::kVbdPrevious},     {gpu::kVbdBefore},
                {gpu::kVbdBeforeLast},   {gpu::kVbdTranslation, Contents::Translation}};
            if (contacts) vbd.push_back({gpu::kVbdContacts, Contents::TwoPerVertex});
            return vbd;
        }
        default:
            return {};
    }
}

}  // namespace

void GpuSolver::generateIntegratorBuffers() {
    for (const IntegratorBuffer& b :
         integratorBuffers(method_, preconditioner_, !scene_.colliders.empty()))
        glGenBuffers(1, &buffers_[b.binding]);
}

// Stage or solver state, as zeros: written by the step before it is read.
void GpuSolver::allocateIntegratorBuffers() {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    for (const IntegratorBuffer& b :
         integratorBuffers(method_, preconditioner_, !scene_.colliders.empty())) {
        const unsigned buffer = buffers_[b.binding];
        switch (b.contents) {
            case Contents::PerVertex:
                bufferData(buffer, nullptr, n * kVec4);
                break;
            case Contents::TwoPerVertex:
                bufferData(buffer, nullptr, 2 * n * kVec4);
                break;
            case Contents::ThreePerVertex:
                bufferData(buffer, nullptr, 3 * n * kVec4);
                break;
            case Contents::Partials: {
                const std::size_t groups = std::size_t(groupsX_) * std::size_t(groupsY_);
                bufferData(buffer, nullptr, (2 * groups + 3) / 4 * kVec4);
                break;
            }
            case Contents::Translation: {
                const std::size_t groups = std::size_t(groupsX_) * std::size_t(groupsY_);
                bufferData(buffer, nullptr, (1 + 3 * groups) * kVec4);
                break;
            }
            case Contents::CgState: {
                const gpu::CgState zero{};
                bufferData(buffer, &zero, sizeof zero);
                break;
            }
        }
    }
}

}  // namespace cloth
