// GpuSolver's self-collision (docs/physics.md "Self-collision"): after each step the passes of
// shaders/compute/self_*.comp, in the order of the CPU backend's CpuSelfCollision::resolve. Two
// round trips a step and one an iteration: the motions' box (the substeps the host loops over)
// and each iteration's contact count (the CPU's early end, which changes nothing but the time).
#include <GL/glew.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"
#include "model/errors.h"
#include "model/self_contact.h"

namespace cloth {
namespace {

constexpr int kIterations = 16;      // as CpuSelfCollision::kIterations
constexpr int kMaxSubsteps = 256;    // as CpuSelfCollision::kMaxSubsteps
constexpr std::size_t kGroup = 256;  // the self passes' work group (self_contact.glsl)

float fromOrderedBits(std::int32_t stored) {
    const std::uint32_t b = std::uint32_t(stored) ^ 0x80000000u;  // back to the uint order
    const std::uint32_t bits = (b & 0x80000000u) != 0 ? b & 0x7fffffffu : ~b;
    float x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

std::size_t bucketsFor(std::size_t n) {
    std::size_t b = 1;
    while (b < 2 * n) b *= 2;
    return b;
}

}  // namespace

void GpuSolver::checkSelfCollisionFits(const Scene& scene) const {
    checkBindingFits(gpu::kSelfInts, "self-collision");
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const std::size_t ints =
        gpu::kSelfHeaderInts + gpu::kSelfIntsPerVertex * n + 3 * bucketsFor(n) + 1;
    const long long limit = context_.info().maxStorageBlockSize;
    if (static_cast<long long>(ints * 4) > limit || static_cast<long long>(n * 112) > limit)
        throw InputError(scene.source, "self_collision",
                         "the " + std::to_string(nu_) + "x" + std::to_string(nv_) +
                             " grid's self-collision buffers exceed " + std::to_string(limit) +
                             " bytes per SSBO on " + context_.info().renderer +
                             ": a coarser grid or the CPU backend");
}

void GpuSolver::allocateSelfCollision(const Scene& scene) {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    selfBuckets_ = bucketsFor(n);
    const std::size_t blocks = (selfBuckets_ + 1 + kGroup - 1) / kGroup;
    const std::size_t ints =
        gpu::kSelfHeaderInts + gpu::kSelfIntsPerVertex * n + 2 * selfBuckets_ + 1 + blocks;
    for (gpu::Binding b : {gpu::kSelfVectors, gpu::kSelfInts}) glGenBuffers(1, &buffers_[b]);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[gpu::kSelfVectors]);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(7 * n * sizeof(glm::vec4)), nullptr,
                 GL_DYNAMIC_COPY);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[gpu::kSelfInts]);
    const std::vector<std::int32_t> zero(ints, 0);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(ints * sizeof(std::int32_t)), zero.data(),
                 GL_DYNAMIC_COPY);
    setSelfUniforms(scene);
    storeSelfStart();
}

void GpuSolver::setSelfUniforms(const Scene& scene) const {
    if (!scene.selfCollision) return;
    const double h = scene.selfCollision->thickness;
    // CpuSelfCollision::setParameters's unit: 64 contacts of ±4h fit 31 bits.
    const float scale = float(std::exp2(std::floor(std::log2(double(1u << 31) / (256.0 * h)))));
    for (Kernel k : selfCollisionKernels()) {
        const unsigned program = programs_[int(k)];
        if (program == 0) continue;
        glProgramUniform1f(program, gpu::kSelfThicknessLocation, float(h));
        glProgramUniform1f(program, gpu::kSelfFrictionLocation,
                           float(scene.selfCollision->friction));
        glProgramUniform1f(program, gpu::kSelfFixedScaleLocation, scale);
    }
}

// x₀ of the next step, the positions copied after the six vectors per vertex (self_finish.comp
// does it after each step; this after an upload or a write).
void GpuSolver::storeSelfStart() const {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_COPY_READ_BUFFER, buffers_[gpu::kPositions]);
    glBindBuffer(GL_COPY_WRITE_BUFFER, buffers_[gpu::kSelfVectors]);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0,
                        GLintptr(6 * n * sizeof(glm::vec4)), GLsizeiptr(n * sizeof(glm::vec4)));
}

namespace {

void readInts(unsigned buffer, std::size_t first, std::size_t count, std::int32_t* out) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(first * sizeof(std::int32_t)),
                       GLsizeiptr(count * sizeof(std::int32_t)), out);
}

}  // namespace

void GpuSolver::runSelfPass(Kernel k, std::size_t invocations) const {
    const std::size_t groups = std::max<std::size_t>(1, (invocations + kGroup - 1) / kGroup);
    const std::size_t x = std::min<std::size_t>(groups, 65535), y = (groups + x - 1) / x;
    glUseProgram(programs_[int(k)]);
    glDispatchCompute(GLuint(x), GLuint(y), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GpuSolver::resolveSelfContacts(long stepNumber) {
    if (selfCollapse_) return;  // the state stays frozen where the cloth collapsed
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const std::size_t scanned = selfBuckets_ + 1;  // the bucket starts
    for (Kernel k : {Kernel::SelfApply, Kernel::SelfFinish})
        glProgramUniform1ui(programs_[int(k)], gpu::kStepLocation, GLuint(stepNumber));
    const std::int32_t header[6] = {INT_MAX, INT_MAX, INT_MAX, INT_MIN, INT_MIN, INT_MIN};
    gpu::subData(buffers_[gpu::kSelfInts], 0, header, sizeof header);
    runSelfPass(Kernel::SelfBegin, n);
    std::int32_t box[6];
    readInts(buffers_[gpu::kSelfInts], 0, 6, box);
    // CpuSelfCollision::chooseSubsteps: m > 4R/h, R half the motions' box diagonal.
    double d2 = 0;
    for (int c = 0; c < 3; ++c) {
        const double e = double(fromOrderedBits(box[3 + c])) - double(fromOrderedBits(box[c]));
        d2 += e * e;
    }
    const double needed =
        std::ceil(4.0 * 0.5 * std::sqrt(d2) / double(scene_.selfCollision->thickness));
    const int substeps =
        std::isfinite(needed) ? int(std::clamp(needed, 1.0, double(kMaxSubsteps))) : kMaxSubsteps;
    ++selfStats_.steps;
    selfStats_.stepsOverBound += !(needed <= double(kMaxSubsteps));
    selfStats_.substeps += substeps;
    selfStats_.mostSubsteps = std::max(selfStats_.mostSubsteps, substeps);
    glProgramUniform1f(programs_[int(Kernel::SelfSubstep)], gpu::kSelfShareLocation,
                       float(1.0 / substeps));
    for (int s = 1; s <= substeps; ++s) {
        runSelfPass(Kernel::SelfSubstep, n);
        for (int it = 0; it < kIterations; ++it) {
            runSelfPass(Kernel::SelfBoxes, std::max(n, (scanned + 3) / 4));
            runSelfPass(Kernel::SelfCount, n);
            runSelfPass(Kernel::SelfScanBlocks, scanned);
            runSelfPass(Kernel::SelfScanSums, kGroup);
            runSelfPass(Kernel::SelfScanAdd, scanned);
            runSelfPass(Kernel::SelfScatter, n);
            runSelfPass(Kernel::SelfContacts, n);
            std::int32_t ends[2];  // the iteration's contacts; its lowest crowded vertex
            readInts(buffers_[gpu::kSelfInts], 7, 2, ends);
            if (ends[1] != INT_MAX) return stopCollapsed(stepNumber, unsigned(ends[1]));
            const std::int32_t found = ends[0];
            ++selfStats_.iterations;
            selfStats_.contacts += found;
            if (it == 0 && s == substeps) selfStats_.lastContacts = found;
            if (found == 0) break;  // nothing would change: as the CPU's early end
            runSelfPass(Kernel::SelfApply, n);
        }
    }
    runSelfPass(Kernel::SelfFinish, n);
}

// A vertex in more contacts than its fixed-point sums hold (model/self_contact.h): the sums may
// have overflowed, so none is applied. The step is marked bad at that vertex, unless the
// integrator marked it already, which leaves the state as the integrator left it, frozen.
void GpuSolver::stopCollapsed(long stepNumber, unsigned vertex) {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    std::int32_t touches = 0;  // the sums: after the header, the cells (4n) and the sorted (n)
    readInts(buffers_[gpu::kSelfInts], gpu::kSelfHeaderInts + 5 * n + 4 * vertex + 3, 1, &touches);
    selfCollapse_ = SelfCollapse{stepNumber, vertex, touches};
    if (readStatus().firstBadStep > std::uint32_t(stepNumber)) {
        const gpu::Status status{std::uint32_t(stepNumber), vertex};
        gpu::subData(buffers_[gpu::kStatus], 0, &status, sizeof status);
    }
    runSelfPass(Kernel::SelfApply, n);  // empties the sums; its y is never finished
}

std::optional<std::string> GpuSolver::selfCollapseReport(const gpu::Status& status) const {
    if (!selfCollapse_ || long(status.firstBadStep) != selfCollapse_->step ||
        status.badVertex != selfCollapse_->vertex)
        return std::nullopt;
    const unsigned k = selfCollapse_->vertex;
    return selfCollapseReason(int(k % unsigned(nu_)), int(k / unsigned(nu_)),
                              selfCollapse_->touches);
}

std::vector<std::int64_t> GpuSolver::selfContactVertices() const {
    if (!features_.selfCollision) return {};
    context_.makeCurrent();
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    std::vector<std::int32_t> flags(n);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    readInts(buffers_[gpu::kSelfInts], gpu::kSelfHeaderInts + 9 * n, n, flags.data());
    std::vector<std::int64_t> k;
    for (std::size_t i = 0; i < n; ++i)
        if (flags[i]) k.push_back(std::int64_t(i));
    return k;
}

}  // namespace cloth
