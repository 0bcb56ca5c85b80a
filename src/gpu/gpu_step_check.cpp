// GpuSolver as the step control's StepCheck (solver/step_check.h): the step's start is copied
// within the GPU (kStepStart), step_check.comp measures each work group's largest growth of a
// structural spring's stretch, and the host reads those maxima (16 bytes a work group) instead
// of the state: 1 kB at 128² with 16x16 work groups, where read() moves 512 kB. The maxima are
// copied into a buffer of their own for that read. Read from the kept state's buffer they cost
// 2.3 times as much a step on an H200 at 1024², likely as the driver then keeps that buffer
// (32 MB) in host memory (docs/performance.md, "The step check on the GPU: its cost").
#include <GL/glew.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"
#include "model/errors.h"
#include "model/grid.h"

namespace cloth {
namespace {

// step_check.comp reads the rest lengths of spring-table slots 0 and 2.
static_assert(kSpringOffsets[0].di == 1 && kSpringOffsets[0].dj == 0 &&
              kSpringOffsets[0].family == Family::Structural);
static_assert(kSpringOffsets[2].di == 0 && kSpringOffsets[2].dj == 1 &&
              kSpringOffsets[2].family == Family::Structural);

}  // namespace

void GpuSolver::checkBindingFits(unsigned binding, const char* feature) const {
    GLint bindings = 0;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &bindings);
    if (bindings <= GLint(binding))
        throw GpuUnavailable(context_.info().renderer + " has " + std::to_string(bindings) +
                             " storage buffer bindings; " + feature + " needs " +
                             std::to_string(binding + 1) + ": use --backend cpu");
}

void GpuSolver::allocateStepCheck() {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const std::size_t groups = std::size_t(groupsX_) * std::size_t(groupsY_);
    const std::size_t bytes = (2 * n + groups) * gpu::kVec4;
    glGenBuffers(1, &buffers_[gpu::kStepStart]);
    if (glBufferStorage != nullptr) {  // GL 4.4 or ARB_buffer_storage
        // Immutable storage with no host access: only the GPU copies into it and reads it, so
        // the driver has no reason to place it in host memory (the H200's check cost 2.3 ms a
        // step more than its kernels at 1024² with glBufferData's storage; docs/performance.md).
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[gpu::kStepStart]);
        glBufferStorage(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, 0);
        glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, nullptr);
    } else {
        gpu::bufferData(buffers_[gpu::kStepStart], nullptr, bytes);
    }
    glGenBuffers(1, &stepMaxima_);
    glBindBuffer(GL_COPY_WRITE_BUFFER, stepMaxima_);
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(groups * gpu::kVec4), nullptr, GL_STREAM_READ);
}

// Positions and velocities into the kept state's buffer (`toKept`), or back out of it.
void GpuSolver::copyKeptState(bool toKept) const {
    const std::size_t bytes = std::size_t(nu_) * std::size_t(nv_) * gpu::kVec4;
    context_.makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the kernels' writes, to the copy
    const gpu::Binding state[] = {gpu::kPositions, gpu::kVelocities};
    for (std::size_t s = 0; s < 2; ++s) {
        const unsigned live = buffers_[state[s]], kept = buffers_[gpu::kStepStart];
        glBindBuffer(GL_COPY_READ_BUFFER, toKept ? live : kept);
        glBindBuffer(GL_COPY_WRITE_BUFFER, toKept ? kept : live);
        const GLintptr keptAt = GLintptr(s * bytes);
        glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, toKept ? 0 : keptAt,
                            toKept ? keptAt : 0, GLsizeiptr(bytes));
    }
}

void GpuSolver::keep() {
    copyKeptState(true);
    keptTime_ = time();
}

double GpuSolver::stretchGrowth() {
    if (!features_.structural) return 0;  // as largestStretchGrowth: no structural spring
    context_.makeCurrent();
    bindBuffers();
    runPass(Kernel::StepCheck);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // its writes, to the read-back
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const std::size_t groups = std::size_t(groupsX_) * std::size_t(groupsY_);
    std::vector<glm::vec4> maxima(groups);
    glBindBuffer(GL_COPY_READ_BUFFER, buffers_[gpu::kStepStart]);
    glBindBuffer(GL_COPY_WRITE_BUFFER, stepMaxima_);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GLintptr(2 * n * gpu::kVec4), 0,
                        GLsizeiptr(groups * gpu::kVec4));
    glGetBufferSubData(GL_COPY_WRITE_BUFFER, 0, GLsizeiptr(groups * gpu::kVec4), maxima.data());
    double largest = 0;
    for (const glm::vec4& m : maxima) {
        if (!(m.x <= std::numeric_limits<float>::max()))  // +inf: a length was not finite
            return std::numeric_limits<double>::infinity();
        largest = std::max(largest, double(m.x));
    }
    return largest;
}

void GpuSolver::restore() {
    copyKeptState(false);
    // The pins' rows need no update: a pinned vertex is where its row holds it, or follows a
    // collider posed by the time.
    startAfresh(keptTime_);
}

}  // namespace cloth
