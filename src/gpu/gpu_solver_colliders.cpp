// GpuSolver's Colliders block (docs/colliders.md §9, src/gpu/gpu_collider_table.h): the still
// records and the meshes' samples when the scene is taken, the moving colliders' poses (with the
// viewer's drags) and the follow pins' motions a batch of kPoseBatch steps at a time as the steps
// reach them.
#include <GL/glew.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"

namespace cloth {

using gpu::kVec4;
using gpu::subData;

// The samples of a baked mesh are uploaded again only when the meshes changed (setParameters
// moving a mesh changes its record, not its grid).
void GpuSolver::uploadColliders(const Scene& scene) {
    colliders_.emplace(scene, dragged_);
    const gpu::ColliderTable& table = *colliders_;
    const std::vector<const void*> sources = table.sampleSources();
    const std::vector<glm::vec4> records = table.stillRecords();
    if (table.vec4Count() != colliderVec4s_) {
        // A new size: the records and samples go in with the allocation, the poses' region as
        // zeros, in one upload. (A clear of a fresh buffer followed at once by a write of part of
        // it is ordered by GL; a driver that defers the clear and writes the part straight into
        // the idle buffer would lose the part. Only this buffer was ever filled that way.)
        colliderVec4s_ = table.vec4Count();
        std::vector<glm::vec4> all(colliderVec4s_, glm::vec4(0));
        std::copy(records.begin(), records.end(), all.begin());
        const std::vector<glm::vec4> samples = table.samples();
        std::copy(samples.begin(), samples.end(),
                  all.begin() + std::ptrdiff_t(table.sampleStart()));
        gpu::bufferData(buffers_[gpu::kColliders], all);
        sampleSources_ = sources;
    } else {
        subData(buffers_[gpu::kColliders], 0, records.data(), records.size() * kVec4);
        if (sources != sampleSources_) {
            const std::vector<glm::vec4> samples = table.samples();
            subData(buffers_[gpu::kColliders], table.sampleStart() * kVec4, samples.data(),
                    samples.size() * kVec4);
            sampleSources_ = sources;
        }
    }
    posedFrom_ = posedTo_ = 0;  // the poses of the new placement (and Δt) are not there yet
}

// How many steps from `first` on have their poses in the batch, after uploading the batch that
// starts at `first` if that one's were missing. Unbounded when nothing moves.
long GpuSolver::posedSteps(long first) {
    if (!colliders_->anyMoving()) return std::numeric_limits<long>::max();
    if (first < posedFrom_ || first >= posedTo_) {
        const std::vector<glm::vec4> batch = colliders_->poseBatch(
            first, [this](long s) { return timeAt(s); }, drags_);
        subData(buffers_[gpu::kColliders], colliders_->poseStart() * kVec4, batch.data(),
                batch.size() * kVec4);
        posedFrom_ = first;
        posedTo_ = first + gpu::kPoseBatch;
    }
    return posedTo_ - first;
}

void GpuSolver::setColliderDrag(int index, const glm::dvec3& offset, const glm::dvec3& velocity) {
    if (index < 0 || std::size_t(index) >= drags_.size())
        throw std::invalid_argument("setColliderDrag: collider " + std::to_string(index) +
                                    " does not exist (the scene has " +
                                    std::to_string(drags_.size()) + ")");
    context_.makeCurrent();
    const std::size_t c = std::size_t(index);
    if (!colliders_->moving(c)) {  // still so far: another variant, with c moving
        dragged_[c] = true;
        try {
            compilePrograms();
        } catch (...) {
            dragged_[c] = false;  // the old kernels run on, undragged
            throw;
        }
        setGrabUniforms(grab_);
        setSelfUniforms(scene_);
        sampleSources_.clear();  // the samples region starts elsewhere now
        uploadColliders(scene_);
    }
    drags_[c] = ColliderDrag{offset, velocity, time()};
    posedFrom_ = posedTo_ = 0;  // posed again, from the next step
}

// Steps first .. first + count − 1, in runs that the uploaded poses cover: one upload per
// kPoseBatch steps, one many-steps dispatch per run at most.
void GpuSolver::runSteps(long first, long count) {
    for (long s = first; s < first + count;) {
        const long run = std::min(first + count - s, posedSteps(s));
        if (manySteps())
            runManySteps(s, run);
        else
            for (long k = s; k < s + run; ++k) {
                dispatchStep(k);
                if (features_.selfCollision) resolveSelfContacts(k);
            }
        s += run;
    }
}

}  // namespace cloth
