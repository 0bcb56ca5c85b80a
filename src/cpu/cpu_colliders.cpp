#include "cpu/cpu_colliders.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "model/mesh_sdf.h"

namespace cloth {
namespace {

template <typename T>
Vec3<T> cast(const glm::dvec3& v) {
    return Vec3<T>(v);
}

// Rounding slack of the row culls: far more than the few ulps by which the cull's arithmetic
// can differ from the response's, far less than anything physical.
template <typename T>
constexpr T kCullSlack = T(64) * std::numeric_limits<T>::epsilon();

template <typename T>
T boundRadius2(T radius) {
    const T r = radius * (T(1) + kCullSlack<T>)+kCullSlack<T>;
    return r * r;
}

// The posed shape in T, and the sphere that bounds where it can touch (thickness h included).
template <typename T>
void setPosed(CpuCollider<T>& c, const PlaneT<double>& s, double) {
    c.shape = PlaneT<T>{cast<T>(s.point), cast<T>(s.normal)};
}
template <typename T>
void setPosed(CpuCollider<T>& c, const SphereT<double>& s, double h) {
    c.shape = SphereT<T>{cast<T>(s.center), T(s.radius)};
    c.boundCenter = cast<T>(s.center);
    c.boundRadius2 = boundRadius2(T(s.radius + h));
}
template <typename T>
void setPosed(CpuCollider<T>& c, const BoxT<double>& s, double h) {
    c.shape = BoxT<T>{cast<T>(s.center), cast<T>(s.halfExtents), Mat3<T>(s.rotation)};
    c.boundCenter = cast<T>(s.center);
    c.boundRadius2 = boundRadius2(T(glm::length(s.halfExtents) + h));
}
template <typename T>
void setPosed(CpuCollider<T>& c, const CapsuleT<double>& s, double h) {
    c.shape = CapsuleT<T>{cast<T>(s.a), cast<T>(s.b), T(s.radius)};
    c.boundCenter = cast<T>(0.5 * (s.a + s.b));
    c.boundRadius2 = boundRadius2(T(0.5 * glm::length(s.b - s.a) + s.radius + h));
}
// Outside the grid φ grows with the distance from it (collider_shapes.h), and on its border φ is
// about the band, more than h: the grid's box bounds the contact (one cell of slack for the
// interpolation).
template <typename T>
void setPosed(CpuCollider<T>& c, const SdfColliderT<double>& s, double h) {
    c.shape = SdfColliderT<T>{s.grid, Mat3<T>(s.rotation), cast<T>(s.translation)};
    const SdfGrid& g = *s.grid;
    const glm::dvec3 half = 0.5 * g.cell * glm::dvec3(g.count - 1);
    c.boundCenter = cast<T>(s.rotation * (g.origin + half) + s.translation);
    c.boundRadius2 = boundRadius2(T(glm::length(half) + g.cell + h));
}

// Whether any vertex of the row may touch, through the row kernels' culls (vectorised); the
// response itself then decides per vertex, so the result is the same bits as without the cull.
template <typename T>
bool rowMayTouch(const CpuCollider<T>& c, ConstRow3<T> x, int n, const RowKernels<T>& kernels) {
    CullRow<T> cull{};
    if (const PlaneT<T>* pl = std::get_if<PlaneT<T>>(&c.shape)) {
        const Vec3<T> q = pl->point, m = pl->normal;
        const T h = c.params.thickness;
        cull.cx = q.x, cull.cy = q.y, cull.cz = q.z, cull.mx = m.x, cull.my = m.y, cull.mz = m.z;
        cull.h = h;
        cull.qMag = std::abs(q.x) + std::abs(q.y) + std::abs(q.z) + std::abs(h);
        cull.slack = kCullSlack<T>;
        return kernels.planeMayTouch(x, cull, n);
    }
    cull.cx = c.boundCenter.x, cull.cy = c.boundCenter.y, cull.cz = c.boundCenter.z;
    cull.radius2 = c.boundRadius2;
    return kernels.sphereMayTouch(x, cull, n);
}

}  // namespace

template <typename T>
void CpuColliders<T>::take(const Scene& scene) {
    std::vector<std::optional<ColliderDrag>> drags;
    if (rest_.size() == scene.colliders.size())
        for (const Rest& r : rest_) drags.push_back(r.drag);  // the viewer's drags persist
    rest_.clear();
    posed_.clear();
    meshes_.clear();
    anyMoving_ = false;
    for (const Collider& c : scene.colliders) {
        if (const MeshCollider* m = c.as<MeshCollider>()) meshes_.push_back(m->baked);
        Rest r{restShape(c.shape), std::nullopt, std::nullopt};
        if (c.motion) r.motion = c.motion->motion();
        CpuCollider<T> p;
        p.params = {T(c.thickness), T(c.friction)};
        p.moving = c.motion.has_value();
        anyMoving_ = anyMoving_ || p.moving;
        std::visit([&](const auto& s) { setPosed(p, s, c.thickness); }, r.shape);
        rest_.push_back(std::move(r));
        posed_.push_back(p);
    }
    for (std::size_t k = 0; k < drags.size(); ++k) {
        rest_[k].drag = drags[k];
        if (drags[k]) setMoving(k);
    }
}

template <typename T>
void CpuColliders<T>::setMoving(std::size_t k) {
    posed_[k].moving = true;
    anyMoving_ = true;
}

template <typename T>
void CpuColliders<T>::drag(int index, const ColliderDrag& drag) {
    if (index < 0 || std::size_t(index) >= rest_.size())
        throw std::invalid_argument("setColliderDrag: collider " + std::to_string(index) +
                                    " does not exist (the scene has " +
                                    std::to_string(rest_.size()) + ")");
    rest_[std::size_t(index)].drag = drag;
    setMoving(std::size_t(index));
}

// The pose at time t: the motion's, then the drag's translation (collider_pose.h's rule).
template <typename T>
void CpuColliders<T>::pose(double t) noexcept {
    for (std::size_t k = 0; k < rest_.size(); ++k) {
        const Rest& r = rest_[k];
        if (!r.motion && !r.drag) continue;
        CpuCollider<T>& c = posed_[k];
        Pose q = r.motion ? poseAt(*r.motion, t) : Pose{};
        RigidVelocity w = r.motion ? velocityAt(*r.motion, t) : RigidVelocity{};
        if (r.drag) {
            q.translation += r.drag->at(t);
            w.linear += r.drag->velocity;
        }
        std::visit([&](const auto& s) { setPosed(c, moved(s, q), double(c.params.thickness)); },
                   r.shape);
        c.linear = cast<T>(w.linear);
        c.angular = cast<T>(w.angular);
        c.origin = cast<T>(w.origin);
    }
}

// The row kernel's view of a plane or sphere.
template <typename T>
ContactRow<T> contactRow(const CpuCollider<T>& c, Row3<T> x, Row3<T> v) {
    ContactRow<T> r{x,
                    v,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    0,
                    c.params.thickness,
                    c.params.friction,
                    c.moving,
                    c.linear.x,
                    c.linear.y,
                    c.linear.z,
                    c.angular.x,
                    c.angular.y,
                    c.angular.z,
                    c.origin.x,
                    c.origin.y,
                    c.origin.z};
    if (const PlaneT<T>* p = std::get_if<PlaneT<T>>(&c.shape)) {
        r.cx = p->point.x, r.cy = p->point.y, r.cz = p->point.z;
        r.nx = p->normal.x, r.ny = p->normal.y, r.nz = p->normal.z;
    } else if (const SphereT<T>* s = std::get_if<SphereT<T>>(&c.shape)) {
        r.cx = s->center.x, r.cy = s->center.y, r.cz = s->center.z;
        r.radius = s->radius;
    }
    return r;
}

template <typename T>
bool CpuColliders<T>::mayTouchRow(ConstRow3<T> x, int n) const {
    const RowKernels<T>& culls = rowKernels<T>(CpuIsa::Generic);  // (any set: the same answers)
    for (const CpuCollider<T>& c : posed_)
        if (rowMayTouch(c, x, n, culls)) return true;
    return false;
}

template <typename T>
bool CpuColliders<T>::applyRow(Row3<T> x, Row3<T> v, int n, const RowKernels<T>& kernels,
                               std::int32_t* touched) const {
    bool mayTouch = false;
    for (std::size_t k = 0; k < posed_.size(); ++k) {
        const CpuCollider<T>& c = posed_[k];
        if (!rowMayTouch(c, ConstRow3<T>(x), n, kernels)) continue;
        mayTouch = true;
        const auto mark = std::int32_t(k + 1);
        if (std::holds_alternative<PlaneT<T>>(c.shape) ||
            std::holds_alternative<SphereT<T>>(c.shape)) {
            ContactRow<T> row = contactRow(c, x, v);
            row.touched = touched;
            row.mark = mark;
            (std::holds_alternative<PlaneT<T>>(c.shape) ? kernels.planeContact
                                                        : kernels.sphereContact)(row, n);
            continue;
        }
        std::visit(
            [&](const auto& s) {
                for (int i = 0; i < n; ++i) {
                    Vec3<T> p(x.x[i], x.y[i], x.z[i]);
                    if (touched) {
                        if (!collidePosition(s, c.params, p)) continue;
                        touched[i] = mark;
                    } else {
                        Vec3<T> w(v.x[i], v.y[i], v.z[i]);
                        applyOne(c, s, p, w);
                        v.x[i] = w.x;
                        v.y[i] = w.y;
                        v.z[i] = w.z;
                    }
                    x.x[i] = p.x;
                    x.y[i] = p.y;
                    x.z[i] = p.z;
                }
            },
            c.shape);
    }
    return mayTouch;
}

template class CpuColliders<float>;
template class CpuColliders<double>;

}  // namespace cloth
