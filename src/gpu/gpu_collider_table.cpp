#include "gpu/gpu_collider_table.h"

#include <algorithm>
#include <cstring>

#include "gpu/gpu_buffers.h"
#include "model/errors.h"
#include "model/mesh_sdf.h"
#include "model/pin_follow.h"

namespace cloth::gpu {
namespace {

constexpr std::size_t kVec4Bytes = 16;

// Copies a record of gpu_layout.h to `out`; returns the vec4 after it.
template <typename Record>
glm::vec4* put(glm::vec4* out, const Record& r) {
    static_assert(sizeof(Record) % sizeof(glm::vec4) == 0);
    std::memcpy(static_cast<void*>(out), &r, sizeof r);
    return out + kVec4sOf<Record>;
}

void columns(const glm::dmat3& m, glm::vec4 (&out)[3]) {
    for (int c = 0; c < 3; ++c) out[c] = vec4(m[c], 0);
}

template <typename... Ts>
struct Overloaded : Ts... {
    using Ts::operator()...;
};
template <typename... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// By the shape's index, in ColliderShape's (and RestShape's) order: plane, sphere, box,
// capsule, mesh.
constexpr int kShapeVec4s[] = {kVec4sOf<PlaneRecord>, kVec4sOf<SphereRecord>, kVec4sOf<BoxRecord>,
                               kVec4sOf<CapsuleRecord>, kVec4sOf<MeshRecord>};
constexpr int kContactVec4s = kVec4sOf<ContactRecord>;
constexpr int kVelocityVec4s = kVec4sOf<VelocityRecord>;
// The GLSL function of shaders/compute/scene_colliders.glsl that collides with such a record.
constexpr const char* kRecordFunctions[] = {"collidePlaneRecord", "collideSphereRecord",
                                            "collideBoxRecord", "collideCapsuleRecord",
                                            "collideMeshRecord"};

}  // namespace

// The scene's shape at t = 0, in double, as CpuColliders takes it (collider_motion.h moves it).
ColliderTable::RestShape ColliderTable::restShape(const ColliderShape& shape) {
    return std::visit(
        Overloaded{
            [](const Plane& p) -> RestShape {
                return PlaneT<double>{p.point, p.normal};
            },
            [](const Sphere& s) -> RestShape {
                return SphereT<double>{s.center, s.radius};
            },
            [](const Box& b) -> RestShape {
                return BoxT<double>{b.center, b.halfExtents, b.rotation.matrix()};
            },
            [](const Capsule& c) -> RestShape {
                return CapsuleT<double>{c.a, c.b, c.radius};
            },
            [](const MeshCollider& m) -> RestShape {
                return SdfColliderT<double>{&m.baked->grid, m.rotation.matrix(), m.translation};
            }},
        shape);
}

ColliderTable::ColliderTable(const Scene& scene, const std::vector<bool>& dragged) {
    // The FollowRecords first in the slot: their offsets, which the pins table holds, do not
    // change when a drag makes another collider moving.
    std::vector<int> follow(scene.colliders.size(), -1);
    for (const Pin& p : scene.pins) {
        if (!follows(scene, p) || follow[std::size_t(p.follow)] >= 0) continue;
        follow[std::size_t(p.follow)] = poseStride_;
        poseStride_ += kVec4sOf<FollowRecord>;
    }
    for (std::size_t n = 0; n < scene.colliders.size(); ++n) {
        const Collider& c = scene.colliders[n];
        const bool moving = c.motion || (n < dragged.size() && dragged[n]);
        Entry e{restShape(c.shape),
                std::nullopt,
                float(c.thickness),
                float(c.friction),
                !moving && c.plain() && (c.as<Plane>() || c.as<Sphere>()),
                moving};
        e.follow = follow[n];
        if (c.motion) e.motion = c.motion->motion();
        const int size = (e.plain ? 0 : kContactVec4s) + kShapeVec4s[c.shape.index()] +
                         (e.moving ? kVelocityVec4s : 0);
        if (e.moving) {
            e.record = poseStride_;
            poseStride_ += size;
        } else {
            e.record = int(recordCount_);
            recordCount_ += std::size_t(size);
        }
        if (const MeshCollider* m = c.as<MeshCollider>()) {
            meshes_.push_back(m->baked);
            e.sampleOffset = (long long)(sampleCount_)*4;  // each mesh from a whole vec4
            sampleCount_ += (m->baked->grid.values.size() + 3) / 4;
        }
        entries_.push_back(std::move(e));
    }
}

std::string ColliderTable::order() const {
    std::string order;
    for (const Entry& e : entries_) {
        if (!order.empty()) order += " ";
        const std::string r = std::to_string(e.record);
        if (e.plain) {
            const bool plane = std::holds_alternative<PlaneT<double>>(e.rest);
            order += (plane ? "PLANE(" : "SPHERE(") + r + ")";
            continue;
        }
        const char* fn = kRecordFunctions[e.rest.index()];
        if (!e.moving) {
            order += std::string("STILL(") + fn + ", " + r + ")";
            continue;
        }
        const int velocity = e.record + kContactVec4s + kShapeVec4s[e.rest.index()];
        order += std::string("MOVING(") + fn + ", pose + " + r + ", pose + " +
                 std::to_string(velocity) + ")";
    }
    return order;
}

void ColliderTable::appendDefines(Defines& d) const {
    if (entries_.empty()) return;
    bool has[5] = {}, plain[2] = {}, contact = false;
    for (const Entry& e : entries_) {
        if (e.plain)
            plain[e.rest.index()] = true;
        else
            has[e.rest.index()] = contact = true;
    }
    if (plain[0]) d.push_back({"HAS_PLANES", ""});
    if (plain[1]) d.push_back({"HAS_SPHERES", ""});
    d.push_back({"HAS_COLLIDERS", ""});
    if (contact) d.push_back({"HAS_CONTACT", ""});
    static const char* const kHas[] = {"HAS_CONTACT_PLANES", "HAS_CONTACT_SPHERES", "HAS_BOXES",
                                       "HAS_CAPSULES", "HAS_MESHES"};
    for (int s = 0; s < 5; ++s)
        if (has[s]) d.push_back({kHas[s], ""});
    if (std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.follow >= 0; }))
        d.push_back({"HAS_FOLLOW_PINS", ""});
    if (anyMoving()) {
        d.push_back({"HAS_MOVING_COLLIDERS", ""});
        d.push_back({"POSE_BASE", std::to_string(poseStart())});
        d.push_back({"POSE_STRIDE", std::to_string(poseStride_)});
        d.push_back({"POSE_BATCH", std::to_string(kPoseBatch)});
    }
    d.push_back({"COLLIDERS_IN_SCENE_ORDER", order()});
}

// Float casts exactly as the CPU float backend's (CpuColliders::pose, setPosed): glm's
// per-component double → float.
void ColliderTable::writeRecord(const Entry& e, const RestShape& posed,
                                const RigidVelocity* velocity, glm::vec4* out) const {
    if (!e.plain) out = put(out, ContactRecord{glm::vec4(e.thickness, e.friction, 0, 0)});
    out = std::visit(
        Overloaded{[&](const PlaneT<double>& s) {
                       return put(out, PlaneRecord{vec4(s.point, 0), vec4(s.normal, 0)});
                   },
                   [&](const SphereT<double>& s) {
                       return put(out, SphereRecord{vec4(s.center, s.radius)});
                   },
                   [&](const BoxT<double>& s) {
                       BoxRecord r{vec4(s.center, 0), vec4(s.halfExtents, 0), {}};
                       columns(s.rotation, r.rotation);
                       return put(out, r);
                   },
                   [&](const CapsuleT<double>& s) {
                       return put(out, CapsuleRecord{vec4(s.a, s.radius), vec4(s.b, 0)});
                   },
                   [&](const SdfColliderT<double>& s) {
                       const SdfGrid& g = *s.grid;
                       MeshRecord r{vec4(g.origin, g.cell),
                                    glm::ivec4(g.count, int(sampleStart() * 4 + e.sampleOffset)),
                                    {},
                                    vec4(s.translation, 0)};
                       columns(s.rotation, r.rotation);
                       return put(out, r);
                   }},
        posed);
    if (velocity != nullptr)
        put(out, VelocityRecord{vec4(velocity->linear, 0), vec4(velocity->angular, 0),
                                vec4(velocity->origin, 0)});
}

std::vector<glm::vec4> ColliderTable::stillRecords() const {
    std::vector<glm::vec4> out(recordCount_, glm::vec4(0));
    for (const Entry& e : entries_)
        if (!e.moving) writeRecord(e, e.rest, nullptr, &out[std::size_t(e.record)]);
    return out;
}

std::vector<glm::vec4> ColliderTable::samples() const {
    std::vector<glm::vec4> out(sampleCount_, glm::vec4(0));
    for (const Entry& e : entries_) {
        const auto* mesh = std::get_if<SdfColliderT<double>>(&e.rest);
        if (mesh == nullptr) continue;
        const std::vector<double>& values = mesh->grid->values;
        for (std::size_t i = 0; i < values.size(); ++i) {
            const std::size_t at = std::size_t(e.sampleOffset) + i;
            out[at / 4][int(at % 4)] = float(values[i]);
        }
    }
    return out;
}

std::vector<const void*> ColliderTable::sampleSources() const {
    std::vector<const void*> out;
    for (const auto& m : meshes_) out.push_back(m.get());
    return out;
}

// The CPU's route (CpuColliders::pose, collider_pose.h): the rest shape moved by the motion's
// pose and the drag's translation, the velocity field the motion's plus the drag's velocity, in
// double, at the end of the step; a FollowRecord from the motion alone (followPinAt).
std::vector<glm::vec4> ColliderTable::poseBatch(
    long first, const std::function<double(long)>& timeOf,
    const std::vector<std::optional<ColliderDrag>>& drags) const {
    std::vector<glm::vec4> out(std::size_t(poseStride_) * kPoseBatch, glm::vec4(0));
    for (long step = first; step < first + kPoseBatch; ++step) {
        const double t = timeOf(step);
        glm::vec4* slot = &out[std::size_t((step - 1) % kPoseBatch) * std::size_t(poseStride_)];
        for (std::size_t n = 0; n < entries_.size(); ++n) {
            const Entry& e = entries_[n];
            if (!e.moving) continue;
            const Pose motion = e.motion ? poseAt(*e.motion, t) : Pose{};
            const RigidVelocity motionVelocity =
                e.motion ? velocityAt(*e.motion, t) : RigidVelocity{};
            if (e.follow >= 0) {
                FollowRecord f{{}, vec4(motion.translation, 0), {}};
                columns(motion.rotation, f.rotation);
                f.velocity = {vec4(motionVelocity.linear, 0), vec4(motionVelocity.angular, 0),
                              vec4(motionVelocity.origin, 0)};
                put(slot + e.follow, f);
            }
            Pose q = motion;
            RigidVelocity w = motionVelocity;
            if (n < drags.size() && drags[n]) {
                q.translation += drags[n]->at(t);
                w.linear += drags[n]->velocity;
            }
            const RestShape posed =
                std::visit([&](const auto& s) { return RestShape(moved(s, q)); }, e.rest);
            writeRecord(e, posed, &w, slot + e.record);
        }
    }
    return out;
}

void ColliderTable::checkFits(long long maxBytes, const std::string& source) const {
    // The kernels unroll one call per collider (COLLIDERS_IN_SCENE_ORDER): past this many,
    // building them takes seconds per collider and gigabytes of the driver's memory (20,000
    // spheres held 11.5 GB after two minutes on llvmpipe).
    constexpr std::size_t kMaxColliders = 64;
    if (entries_.size() > kMaxColliders)
        throw InputError(source, "colliders",
                         std::to_string(entries_.size()) + " colliders: the GPU backend builds " +
                             "each into its kernels and takes at most " +
                             std::to_string(kMaxColliders) + "; use --backend cpu");
    const long long bytes = (long long)(vec4Count() * kVec4Bytes);
    if (bytes <= maxBytes) return;
    std::string key = "colliders";
    std::size_t most = 0;
    for (std::size_t n = 0; n < entries_.size(); ++n) {
        const auto* mesh = std::get_if<SdfColliderT<double>>(&entries_[n].rest);
        if (mesh == nullptr) continue;
        if (mesh->grid->values.size() > most) {
            most = mesh->grid->values.size();
            key = "colliders[" + std::to_string(n) + "].cell";
        }
    }
    throw InputError(source, key,
                     "the GPU backend's collider table needs " + std::to_string(bytes) +
                         " bytes (the mesh grid" +
                         (most > 0 ? " of " + std::to_string(most) + " samples" : std::string()) +
                         " included); the device allows at most " + std::to_string(maxBytes) +
                         " bytes per SSBO: a larger cell makes the grid smaller");
}

}  // namespace cloth::gpu
