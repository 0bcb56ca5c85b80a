// The CPU backend's colliders (docs/colliders.md): every shape with the shared response of
// model/collider_contact.h, posed at the end of each step by model/collider_motion.h. A plane or
// sphere without thickness, friction or motion gets DESIGN.md §2's rule bit for bit from it.
// applyRow() runs one loop per collider over a row of vertices, and first asks, in a branch-free
// loop the compiler vectorises, whether any vertex of the row can touch it: a collider far from the
// row costs that one pass (docs/performance.md).
#pragma once

#include <memory>
#include <variant>
#include <vector>

#include "cpu/cpu_rows.h"
#include "model/collider_contact.h"
#include "model/collider_motion.h"
#include "model/collider_pose.h"
#include "model/scene.h"

namespace cloth {

template <typename T>
struct CpuCollider {
    using Shape = std::variant<PlaneT<T>, SphereT<T>, BoxT<T>, CapsuleT<T>, SdfColliderT<T>>;
    Shape shape;  // posed at the end of the step being taken
    ContactParamsT<T> params;
    // v_c(p) = linear + angular × (p − origin), at the end of the step (moving colliders only).
    bool moving = false;
    Vec3<T> linear{0}, angular{0}, origin{0};
    // A sphere no vertex outside of which can touch the collider (all shapes but the plane):
    // rows with every vertex outside it skip the collider.
    Vec3<T> boundCenter{0};
    T boundRadius2 = 0;

    Vec3<T> velocityAt(const Vec3<T>& p) const {
        return moving ? linear + glm::cross(angular, p - origin) : Vec3<T>(0);
    }
};

template <typename T>
class CpuColliders {
public:
    // The scene's colliders at t = 0 (their rest pose).
    void take(const Scene& scene);
    // Poses the moving ones at time t [s] (the end of the step about to be taken). Allocates
    // nothing: it runs in a barrier's completion.
    void pose(double t) noexcept;
    // Solver::setColliderDrag: collider `index` is displaced by drag.at(t) from the next pose on,
    // and moves (v_c gains drag.velocity).
    // Drags outlive take() while the number of colliders stays. std::invalid_argument for an
    // index out of range.
    void drag(int index, const ColliderDrag& drag);
    bool empty() const { return posed_.empty(); }
    bool anyMoving() const { return anyMoving_; }

    // Every collider in scene order on one vertex.
    void apply(Vec3<T>& p, Vec3<T>& v) const {
        for (const CpuCollider<T>& c : posed_)
            std::visit([&](const auto& s) { applyOne(c, s, p, v); }, c.shape);
    }
    // The surface that touches p last, p moved by each collider as apply() moves it: its velocity
    // v_c (0 for a still one) and its friction coefficient c_f; both 0 where none touches.
    struct Surface {
        Vec3<T> velocity{0};
        T friction = 0;
    };
    // apply()'s positions alone (no velocity), and the surface that touched p last.
    Surface project(Vec3<T>& p) const {
        Surface last;
        for (const CpuCollider<T>& c : posed_)
            std::visit(
                [&](const auto& s) {
                    const Vec3<T> u = c.velocityAt(p);
                    if (collidePosition(s, c.params, p)) last = {u, c.params.friction};
                },
                c.shape);
        return last;
    }
    Surface surfaceAt(Vec3<T> p) const { return project(p); }
    // surfaceAt(p) where applyRow's `touched` gave p's mark: the same surface, without running the
    // colliders again where the one that touched last stands still.
    Surface surfaceOf(std::int32_t mark, const Vec3<T>& p) const {
        if (mark == 0) return {};
        const CpuCollider<T>& c = posed_[mark - 1];
        return c.moving ? surfaceAt(p) : Surface{Vec3<T>(0), c.params.friction};
    }
    Vec3<T> surfaceVelocity(const Vec3<T>& p) const { return surfaceAt(p).velocity; }
    // Whether any collider may touch one of the n positions of x (a conservative cull: false
    // only where none touches).
    bool mayTouchRow(ConstRow3<T> x, int n) const;
    // The same on the n vertices of a row of positions x and velocities v; planes and spheres
    // through the row kernels (the same bits, vectorised). False where no collider could touch
    // the row (x and v unchanged). With `touched` (n entries, set to 0 by the caller), project()'s
    // positions alone, v left as it is, and touched[i] the mark of the collider that touched
    // vertex i last (its index + 1, surfaceOf).
    bool applyRow(Row3<T> x, Row3<T> v, int n, const RowKernels<T>& kernels,
                  std::int32_t* touched = nullptr) const;

private:
    struct Rest {
        ShapeD shape;
        std::optional<Motion> motion;
        std::optional<ColliderDrag> drag;
    };
    void setMoving(std::size_t k);

    // With h = 0, c_f = 0 and a still collider, the response is DESIGN.md §2's rule bit for bit
    // (tests/model/collider_contact_test.cpp): there is no second copy of it for plain colliders.
    template <typename S>
    static void applyOne(const CpuCollider<T>& c, const S& s, Vec3<T>& p, Vec3<T>& v) {
        collide(s, c.params, c.velocityAt(p), p, v);
    }

    std::vector<Rest> rest_;
    std::vector<CpuCollider<T>> posed_;
    std::vector<std::shared_ptr<const BakedMesh>> meshes_;  // keep the grids alive
    bool anyMoving_ = false;
};

extern template class CpuColliders<float>;
extern template class CpuColliders<double>;

}  // namespace cloth
