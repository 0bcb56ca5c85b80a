// The Colliders storage block (binding 5) of the GPU backend, docs/colliders.md §9: one record
// per collider in scene order, the mesh colliders' signed-distance samples, and a batch of the
// moving colliders' poses for the coming steps. No GL here: the variant (gpuDefines), the size
// check and the tests use it freely; GpuSolver uploads what it builds.
//
// Three regions of vec4s, in this order:
//   records  the still colliders' records, each at the offset its macro names;
//   samples  the meshes' SDF samples, four floats per vec4 (sample i of the buffer at
//            colliders[i / 4][i % 4], each mesh from the index in its record);
//   poses    kPoseBatch slots of poseStride vec4s: the moving colliders' records posed at the
//            end of step s (the solver's time then, as the CPU poses them) in slot
//            (s − 1) mod kPoseBatch, after a FollowRecord per collider that pins follow.
// A collider is moving when it has a motion or is dragged (compiled as moving: `dragged`).
// A record: a ContactRecord (h, c_f) unless the collider is plain (DESIGN.md §2's plane or
// sphere), the shape's record, and for a moving collider its VelocityRecord (gpu_layout.h).
#pragma once

#include <cstddef>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "gpu/gpu_layout.h"
#include "gpu/shader_loader.h"
#include "model/collider_motion.h"
#include "model/collider_pose.h"
#include "model/scene.h"

namespace cloth::gpu {

// Steps whose poses one upload carries: the steps between two status reads (checkEvery's
// default), so that a run uploads once per read.
inline constexpr int kPoseBatch = 64;

// vec4s per record (gpu_layout.h's record structs, as scene_colliders.glsl reads them).
template <typename Record>
inline constexpr int kVec4sOf = int(sizeof(Record) / 16);

class ColliderTable {
public:
    // dragged[c]: collider c is compiled as moving although it may have no motion (the
    // viewer's drag); missing entries: false.
    explicit ColliderTable(const Scene& scene, const std::vector<bool>& dragged = {});

    // HAS_COLLIDERS and what the scene's colliders need compiled (HAS_PLANES, HAS_SPHERES for
    // plain ones; HAS_CONTACT, HAS_CONTACT_PLANES, HAS_CONTACT_SPHERES, HAS_BOXES, HAS_CAPSULES,
    // HAS_MESHES; HAS_MOVING_COLLIDERS, POSE_BASE, POSE_STRIDE, POSE_BATCH) and
    // COLLIDERS_IN_SCENE_ORDER. Nothing when the scene has no collider.
    void appendDefines(Defines& d) const;

    bool empty() const { return entries_.empty(); }
    bool anyMoving() const { return poseStride_ > 0; }
    bool moving(std::size_t collider) const { return entries_.at(collider).moving; }
    // The FollowRecord's vec4 offset in a pose slot of a collider that pins follow; −1 if none.
    int followRecord(std::size_t collider) const { return entries_.at(collider).follow; }
    std::size_t sampleStart() const { return recordCount_; }               // vec4 index
    std::size_t poseStart() const { return recordCount_ + sampleCount_; }  // vec4 index
    std::size_t vec4Count() const { return poseStart() + std::size_t(poseStride_) * kPoseBatch; }

    // The records region (vec4s 0 .. sampleStart()).
    std::vector<glm::vec4> stillRecords() const;
    // The samples region, from sampleStart().
    std::vector<glm::vec4> samples() const;
    // The meshes whose samples the table holds, in scene order: equal lists, equal samples.
    std::vector<const void*> sampleSources() const;
    // The poses region for steps first .. first + kPoseBatch − 1 (each in its slot), step s at
    // time timeOf(s) [s], collider c displaced by drags[c] if it has one (model/collider_pose.h).
    std::vector<glm::vec4> poseBatch(long first, const std::function<double(long)>& timeOf,
                                     const std::vector<std::optional<ColliderDrag>>& drags) const;

    // InputError when the scene has more than 64 colliders (the kernels unroll each), or when
    // the block exceeds `maxBytes` (one SSBO binding): naming the key colliders[n].cell of the
    // mesh with the most samples (colliders otherwise).
    void checkFits(long long maxBytes, const std::string& source) const;

private:
    using RestShape = std::variant<PlaneT<double>, SphereT<double>, BoxT<double>, CapsuleT<double>,
                                   SdfColliderT<double>>;
    struct Entry {
        RestShape rest;  // the scene's shape at t = 0
        std::optional<Motion> motion;
        float thickness, friction;
        bool plain;       // DESIGN.md §2's plane or sphere: shape only, today's code
        bool moving;      // a motion or a drag: posed per step
        int record = 0;   // vec4 index: in the records region, or in a pose slot if moving
        int follow = -1;  // its FollowRecord's vec4 index in a pose slot; −1: no pin follows it
        long long sampleOffset = 0;  // mesh: its first sample's float index in the samples
    };

    static RestShape restShape(const ColliderShape& shape);
    void writeRecord(const Entry& e, const RestShape& posed, const RigidVelocity* velocity,
                     glm::vec4* out) const;
    std::string order() const;

    std::vector<Entry> entries_;
    std::vector<std::shared_ptr<const BakedMesh>> meshes_;  // keep the grids alive
    std::size_t recordCount_ = 0;                           // vec4s of still records
    std::size_t sampleCount_ = 0;                           // vec4s of packed samples
    int poseStride_ = 0;                                    // vec4s per pose slot
};

}  // namespace cloth::gpu
