// GpuSolver's interactive control (the viewer, Solver's second half): small buffer updates and
// two uniforms, never a recompilation (a drag may need one: gpu_solver_colliders.cpp). Each takes
// effect from the next step, and each discards the forces verlet kept from the last step
// (docs/integrators.md).
#include <GL/glew.h>

#include <map>
#include <set>
#include <stdexcept>
#include <vector>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"
#include "model/pin_follow.h"
#include "model/vbd_local.h"

namespace cloth {

using gpu::bufferData;
using gpu::kVec4;
using gpu::subData;
using gpu::vec4;

void GpuSolver::write(const SimState& state) {
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    if (state.nu != nu_ || state.nv != nv_ || state.positions.size() != n ||
        state.velocities.size() != n)
        throw std::invalid_argument("write: the state is for another grid");
    std::vector<glm::vec4> x(n), v(n);
    for (std::size_t k = 0; k < n; ++k) {
        x[k] = vec4(state.positions[k], inverseMass_[k]);
        v[k] = vec4(state.velocities[k], 0);
    }
    for (const auto& [k, pin] : pinSlots_) {
        v[std::size_t(k)].w = float(pin.slot);
        if (!pin.pinned) continue;
        x[std::size_t(k)].w = 0;
        if (following_.count(k) != 0) continue;  // its row holds its rest position
        pins_[std::size_t(pin.slot)] = glm::vec4(glm::vec3(x[std::size_t(k)]), 0);  // held here
    }
    context_.makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    subData(buffers_[gpu::kPositions], 0, x.data(), n * kVec4);
    subData(buffers_[gpu::kVelocities], 0, v.data(), n * kVec4);
    subData(buffers_[gpu::kPins], 0, pins_.data(), pins_.size() * kVec4);
    startAfresh(state.time);
}

void GpuSolver::startAfresh(double time) {
    setTime(time);
    vbdHistoryFrom_ = steps_ + 2;                   // the written velocities have no predecessor
    posedFrom_ = posedTo_ = 0;                      // posed again at the (new) time
    if (features_.selfCollision) storeSelfStart();  // the next step starts here
    // No last solution to start from, nor grips or contacts, as on the CPU.
    std::vector<gpu::Binding> cleared;
    if (method_ == Method::ImplicitEuler) cleared = {gpu::kCgVelocityChange, gpu::kCgContacts};
    if (method_ == Method::Vbd) cleared = {gpu::kVbdContacts};
    for (gpu::Binding b : cleared) {
        if (b != gpu::kCgVelocityChange && scene_.colliders.empty()) continue;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[b]);
        glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, nullptr);
    }
    // A written state starts afresh: an earlier instability no longer freezes the kernels.
    const gpu::Status status = gpu::kStable;
    subData(buffers_[gpu::kStatus], 0, &status, sizeof status);
    selfCollapse_.reset();
    forcesKept_ = false;
    computeNormals();
}

// Pinning reads the vertex back (16 bytes) and holds it there at rest; releasing gives it its
// inverse mass again, so it moves on from where it is with its velocity. As on the CPU, a vertex
// that follows a collider keeps following when pinned again, and stops when released.
void GpuSolver::setPinned(int i, int j, bool pinned) {
    if (i < 0 || j < 0 || i >= nu_ || j >= nv_)
        throw std::invalid_argument("setPinned: vertex outside the grid");
    const std::int64_t k = std::int64_t(j) * nu_ + i;
    auto it = pinSlots_.find(k);
    if (!pinned && (it == pinSlots_.end() || !it->second.pinned)) return;
    forcesKept_ = false;
    if (pinned && following_.count(k) != 0) return;  // pinned, and following, already
    context_.makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::size_t at = std::size_t(k) * kVec4;
    if (!pinned) {
        it->second.pinned = false;
        following_.erase(k);
        pins_[std::size_t(it->second.slot)].w = 0;  // re-pinned, it is a still pin
        subData(buffers_[gpu::kPositions], at + 3 * sizeof(float), &inverseMass_[std::size_t(k)],
                sizeof(float));
        return;
    }
    if (it == pinSlots_.end()) {
        it = pinSlots_.emplace(k, PinSlot{int(pins_.size()), true}).first;
        pins_.emplace_back(0);
    }
    it->second.pinned = true;
    glm::vec4 x = gpu::readElement(buffers_[gpu::kPositions], k);
    pins_[std::size_t(it->second.slot)] = glm::vec4(glm::vec3(x), 0);
    storePin(it->second.slot);
    x.w = 0;
    const glm::vec4 v(0, 0, 0, float(it->second.slot));
    subData(buffers_[gpu::kPositions], at, &x, kVec4);
    subData(buffers_[gpu::kVelocities], at, &v, kVec4);
}

// Row `slot` of pins_ to the GPU; a full table is reallocated at twice the size.
void GpuSolver::storePin(int slot) {
    if (pins_.size() <= pinCapacity_) {
        subData(buffers_[gpu::kPins], std::size_t(slot) * kVec4, &pins_[std::size_t(slot)], kVec4);
        return;
    }
    pinCapacity_ = 2 * pins_.size();
    std::vector<glm::vec4> table = pins_;
    table.resize(pinCapacity_, glm::vec4(0));
    bufferData(buffers_[gpu::kPins], table);
}

// Two uniforms of the kernels that see the grab: no buffer traffic, no recompilation.
void GpuSolver::setGrab(const std::optional<Grab>& grab) {
    if (grab && (grab->vertex < 0 || grab->vertex >= std::int64_t(nu_) * nv_))
        throw std::invalid_argument("setGrab: vertex outside the grid");
    context_.makeCurrent();
    setGrabUniforms(grab);
    grab_ = grab;
    forcesKept_ = false;
}

// Everything but the compiled variant is data: the Params block and the Colliders records are
// rewritten in place (a collider's placement, thickness, friction, motion), and new masses
// rewrite position.w. Checks come first, so a refused scene changes nothing.
void GpuSolver::setParameters(const Scene& scene) {
    if (scene.cloth.nu != nu_ || scene.cloth.nv != nv_)
        throw std::invalid_argument("setParameters: the grid size differs; build a new solver");
    if (!(Features::of(scene) == features_))
        throw std::invalid_argument("setParameters: the features differ; build a new solver");
    if (gpuDefines(scene, workGroup_, dragged_) != defines_)
        throw std::invalid_argument(
            "setParameters: the scene compiles to another GPU kernel (collider order or "
            "integrator); build a new solver");
    gpu::ColliderTable(scene, dragged_)
        .checkFits(context_.info().maxStorageBlockSize, scene.source);
    const Grid g = scene.grid();
    std::set<std::int64_t> scenePins, pinnedNow;
    for (const Pin& p : scene.pins) scenePins.insert(g.index(p.i, p.j));
    for (const auto& [k, pin] : pinSlots_)
        if (pin.pinned) pinnedNow.insert(k);
    std::map<std::int64_t, int> follows;
    for (const FollowPin& f : followPins(scene)) follows[f.vertex] = f.collider;
    if (scenePins != pinnedNow || follows != following_)
        throw std::invalid_argument("setParameters: the pins differ; use setPinned");
    context_.makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    setStepDt(scene.integrator.dt);  // the time goes on from where it is
    scene_ = scene;
    maxSpeed_ = scene.maxSpeed;
    maxIterations_ = scene.integrator.maxIterations;
    vbdIterations_ = scene.integrator.iterations;
    chebyshevRho_ = scene.integrator.chebyshevRho;
    translationSweeps_ = scene.integrator.translationSweeps;
    translationLevels_ = vbdTranslationLevels(scene.integrator.translationLevels,
                                              scene.integrator.translationBlockWidth, nu_, nv_);
    translationLevelPasses_ = scene.integrator.translationLevelPasses;
    forcesKept_ = false;
    uploadParams(scene);
    setSelfUniforms(scene);
    uploadColliders(scene);
    updateInverseMass(scene);
}

std::vector<float> GpuSolver::inverseMasses(const Scene& scene) {
    const Grid g = scene.grid();
    std::vector<float> w(std::size_t(g.count()));
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i)
            w[std::size_t(g.index(i, j))] = float(1.0 / scene.vertexMass(i, j));  // as the CPU's
    return w;
}

// position.w of every free vertex (pinned ones keep 0) from the scene's masses, each vertex its
// own (a new cloth.mass scales them all; a material's lumped masses keep their ratios): one
// read-back and upload of the positions, only when a mass changed.
void GpuSolver::updateInverseMass(const Scene& scene) {
    std::vector<float> inverseMass = inverseMasses(scene);
    if (inverseMass == inverseMass_) return;
    inverseMass_ = std::move(inverseMass);
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    std::vector<glm::vec4> x = gpu::downloadVec4(buffers_[gpu::kPositions], n);
    for (std::size_t k = 0; k < n; ++k)
        if (x[k].w != 0) x[k].w = inverseMass_[k];
    subData(buffers_[gpu::kPositions], 0, x.data(), n * kVec4);
}

}  // namespace cloth
