// The reference model, DESIGN.md §2, written out as directly as possible: forces, pins, colliders
// and energies. The bending energy is in reference_bending.cpp, the integrators in
// reference_integrators.cpp.
#include "reference/reference.h"

#include <cmath>

#include "reference/reference_colliders.h"
#include "reference/vector_ops.h"

namespace ref {
namespace {

// The 12 neighbour offsets of the §2 table; family 0 structural, 1 shear, 2 bend.
struct Offset {
    int di, dj, family;
};
constexpr Offset kOffsets[12] = {
    {1, 0, 0}, {-1, 0, 0}, {0, 1, 0},  {0, -1, 0},   // structural
    {1, 1, 1}, {-1, 1, 1}, {1, -1, 1}, {-1, -1, 1},  // shear
    {2, 0, 2}, {-2, 0, 2}, {0, 2, 2},  {0, -2, 2},   // bend
};
// One offset of each opposite pair, so that every spring is visited once for its energy.
constexpr Offset kHalfOffsets[6] = {
    {1, 0, 0}, {0, 1, 0}, {1, 1, 1}, {-1, 1, 1}, {2, 0, 2}, {0, 2, 2},
};

int resolve(int index, int count) {
    return index < 0 ? index + count : index;
}

}  // namespace

Simulation::Simulation(const Params& p) : prm_(p) {
    du_ = prm_.nu > 1 ? prm_.sizeU / (prm_.nu - 1) : 0.0;
    dv_ = prm_.nv > 1 ? prm_.sizeV / (prm_.nv - 1) : 0.0;
    u_ = normalised(prm_.uAxis);
    vAxis_ = normalised(prm_.vAxis);
    wind_ = prm_.wind ? normalised(prm_.windDirection) : V3{0, 0, 0};
    for (Collider& c : prm_.colliders) {
        if (!c.isSphere) c.plane.normal = normalised(c.plane.normal);
    }
    const int n = prm_.nu * prm_.nv;
    mass_.assign(n, prm_.density > 0 ? 0.0 : prm_.mass);
    if (prm_.density > 0) {
        const double quarter = prm_.density * du_ * dv_ / 4;
        for (int j = 0; j + 1 < prm_.nv; ++j) {
            for (int i = 0; i + 1 < prm_.nu; ++i) {
                for (int corner : {j * prm_.nu + i, j * prm_.nu + i + 1, (j + 1) * prm_.nu + i,
                                   (j + 1) * prm_.nu + i + 1})
                    mass_[corner] += quarter;
            }
        }
    }
    pinned_.assign(n, false);
    follow_.assign(n, -1);
    for (std::size_t k = 0; k < prm_.pins.size(); ++k) {
        const auto& pin = prm_.pins[k];
        const int i = resolve(pin[0], prm_.nu), j = resolve(pin[1], prm_.nv);
        pinned_[j * prm_.nu + i] = true;
        if (k < prm_.pinFollow.size()) follow_[j * prm_.nu + i] = prm_.pinFollow[k];
    }
    rest_.resize(n);
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) rest_[j * prm_.nu + i] = restPosition(i, j);
    }
    p_ = rest_;
    v_.assign(n, V3{0, 0, 0});
    grip_.assign(n, 0.0);
    pin(p_, v_);  // follow pins start at their pose at t = 0
}

void Simulation::setState(const std::vector<V3>& p, const std::vector<V3>& v) {
    if (p.size() == p_.size() && v.size() == v_.size()) {
        p_ = p;
        v_ = v;
        verletForces_.clear();
        grip_.assign(p_.size(), 0.0);
    }
}

V3 Simulation::restPosition(int i, int j) const {
    return add(prm_.origin, add(scale(i * du_, u_), scale(j * dv_, vAxis_)));
}

double Simulation::stiffness(int i, int j, int di, int dj, int family) const {
    double k = family == 0 ? prm_.kStructural : family == 1 ? prm_.kShear : prm_.kBend;
    for (const Params::OffsetStiffness& o : prm_.offsetStiffness) {
        if (o.di == di && o.dj == dj) k = o.k;
    }
    if (!prm_.cellShares || family != 0) return k;
    // The cells beside the edge from (i, j) to (i + di, j + dj): along u those of cell rows
    // j − 1 and j, along v those of cell columns i − 1 and i, where they exist.
    const int line = dj == 0 ? j : i, cells = dj == 0 ? prm_.nv - 1 : prm_.nu - 1;
    const int beside = (line - 1 >= 0 ? 1 : 0) + (line < cells ? 1 : 0);
    return k * beside / 2;
}

double Simulation::drag(int k) const {
    return prm_.damping + prm_.dampingRate * mass_[k];
}

double Simulation::restLength(int di, int dj) const {
    return norm(add(scale(di * du_, u_), scale(dj * dv_, vAxis_)));
}

// Σ over existing neighbours of K (|d| − L) d/|d|, d = p_q − p_k (seed eq. (2)).
V3 Simulation::springForces(const std::vector<V3>& p, int i, int j) const {
    V3 f{0, 0, 0};
    const V3& pk = p[j * prm_.nu + i];
    for (const Offset& o : kOffsets) {
        const double k = stiffness(i, j, o.di, o.dj, o.family);
        const int qi = i + o.di, qj = j + o.dj;
        if (k == 0 || qi < 0 || qi >= prm_.nu || qj < 0 || qj >= prm_.nv) continue;
        const double len = restLength(o.di, o.dj);
        const V3 d = sub(p[qj * prm_.nu + qi], pk);
        const double dist = norm(d);
        if (dist < 1e-12 * len) continue;
        f = add(f, scale(k * (dist - len) / dist, d));
    }
    return f;
}

// Each spring a→b once (the offsets that point up the grid, or along +u in a row), with
// F_a = β K ((w_b − w_a)·d̂) d̂ and F_b = −F_a; nothing for a spring shorter than 1e-12 L.
void Simulation::addSpringDamping(const std::vector<V3>& x, const std::vector<V3>& w,
                                  std::vector<V3>& f) const {
    if (prm_.springDamping == 0) return;
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) {
            for (const Offset& o : kOffsets) {
                if (o.dj < 0 || (o.dj == 0 && o.di < 0)) continue;  // the other end counts it
                const double k = stiffness(i, j, o.di, o.dj, o.family);
                const int qi = i + o.di, qj = j + o.dj;
                if (k == 0 || qi < 0 || qi >= prm_.nu || qj < 0 || qj >= prm_.nv) continue;
                const int a = j * prm_.nu + i, b = qj * prm_.nu + qi;
                const V3 d = sub(x[b], x[a]);
                const double dist = norm(d);
                if (dist < 1e-12 * restLength(o.di, o.dj)) continue;
                const V3 dhat = scale(1.0 / dist, d);
                const V3 fa = scale(prm_.springDamping * k * dot(sub(w[b], w[a]), dhat), dhat);
                f[a] = add(f[a], fa);
                f[b] = sub(f[b], fa);
            }
        }
    }
}

// docs/integrators.md, implicit_euler: per spring J_s = K (d̂ d̂ᵀ + max(0, 1 − L/l) (I − d̂ d̂ᵀ)),
// 0 when l < 1e-12 L; (H w)_k = Σ_springs of k J_s (w_k − w_q), pinned rows and columns removed.
std::vector<V3> Simulation::hessianProduct(const std::vector<V3>& x, const std::vector<V3>& w,
                                           bool pinnedColumns) const {
    const V3 zero{0, 0, 0};
    std::vector<V3> y(x.size(), zero);
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) {
            const int k = j * prm_.nu + i;
            if (pinned_[k]) continue;
            for (const Offset& o : kOffsets) {
                const double stiff = stiffness(i, j, o.di, o.dj, o.family);
                const int qi = i + o.di, qj = j + o.dj;
                if (stiff == 0 || qi < 0 || qi >= prm_.nu || qj < 0 || qj >= prm_.nv) continue;
                const int q = qj * prm_.nu + qi;
                const double len = restLength(o.di, o.dj);
                const V3 d = sub(x[q], x[k]);
                const double dist = norm(d);
                if (dist < 1e-12 * len) continue;
                const V3 dhat = scale(1.0 / dist, d);
                const double transverse = std::fmax(0.0, 1.0 - len / dist);
                const V3 e = sub(w[k], pinned_[q] && !pinnedColumns ? zero : w[q]);
                const V3 along = scale(dot(dhat, e), dhat);  // d̂ d̂ᵀ e
                y[k] = add(y[k], scale(stiff, add(along, scale(transverse, sub(e, along)))));
            }
        }
    }
    // H_b w = −F_b(w); pinned rows stay 0.
    std::vector<V3> fb(x.size(), zero);
    addBending(w, fb, pinnedColumns);
    for (std::size_t k = 0; k < y.size(); ++k)
        if (!pinned_[k]) y[k] = sub(y[k], fb[k]);
    return y;
}

// K_w ⟨n, û_w⟩ n with the central-difference vertex normal of §2 (seed §5.3).
V3 Simulation::windForce(const std::vector<V3>& p, int i, int j) const {
    const int nu = prm_.nu, nv = prm_.nv;
    const int ip = i + 1 < nu - 1 ? i + 1 : nu - 1, im = i - 1 > 0 ? i - 1 : 0;
    const int jp = j + 1 < nv - 1 ? j + 1 : nv - 1, jm = j - 1 > 0 ? j - 1 : 0;
    const V3 a = sub(p[j * nu + ip], p[j * nu + im]);
    const V3 b = sub(p[jp * nu + i], p[jm * nu + i]);
    const V3 axb = cross(a, b);
    const double len = norm(axb);
    if (len < 1e-12) return {0, 0, 0};
    const V3 n = scale(1.0 / len, axb);
    // A material's K_w is a pressure on the vertex's area, its mass over the density.
    const double area = prm_.density > 0 ? mass_[std::size_t(j * prm_.nu + i)] / prm_.density : 1;
    return scale(area * prm_.windStrength * dot(n, wind_), n);
}

// Plane (Q12): project onto it and cancel the normal velocity. Sphere (Q13): push to the surface
// and cancel the radial velocity. In the order the scene lists them.
void Simulation::applyColliders(V3& p, V3& v) const {
    for (const Collider& c : prm_.colliders) applyCollider(c, p, v);
}

// The velocity of the surface that touches p last (p moved by each collider in turn), 0 for a
// still one or where none touches.
V3 Simulation::surfaceVelocity(V3 p) const {
    V3 vc{0, 0, 0};
    for (const Collider& c : prm_.colliders) {
        const V3 before = p;
        const V3 u = c.extended ? motionVelocity(c.motion, colliderTime_, p) : V3{0, 0, 0};
        V3 v{0, 0, 0};
        applyCollider(c, p, v);
        if (p[0] != before[0] || p[1] != before[1] || p[2] != before[2]) vc = u;
    }
    return vc;
}

void Simulation::applyCollider(const Collider& c, V3& p, V3& v) const {
    if (c.extended) {
        collideMoving(c, colliderTime_, p, v);
    } else if (!c.isSphere) {
        const V3& n = c.plane.normal;
        const double s = dot(sub(p, c.plane.point), n);
        if (s < 0) {
            p = sub(p, scale(s, n));
            v = sub(v, scale(dot(v, n), n));
        }
    } else {
        const V3 r = sub(p, c.sphere.center);
        const double len = norm(r);
        if (len < c.sphere.radius) {
            const V3 n = len == 0 ? V3{0, 1, 0} : scale(1.0 / len, r);
            p = add(c.sphere.center, scale(c.sphere.radius, n));
            v = sub(v, scale(dot(v, n), n));
        }
    }
}

std::vector<V3> Simulation::forces(const std::vector<V3>& p) const {
    std::vector<V3> f(p.size());
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) {
            V3 fk = springForces(p, i, j);
            if (prm_.wind) fk = add(fk, windForce(p, i, j));
            f[j * prm_.nu + i] = fk;
        }
    }
    addBending(p, f);
    return f;
}

// docs/integrators.md: a(x, v) = (F(x) + F_β(x, v) − μ_k v)/m_k + g; a pinned vertex's is not
// used (0 here).
std::vector<V3> Simulation::accelerations(const std::vector<V3>& x,
                                          const std::vector<V3>& v) const {
    std::vector<V3> f = forces(x);
    addSpringDamping(x, v, f);
    std::vector<V3> a(x.size(), V3{0, 0, 0});
    for (std::size_t k = 0; k < x.size(); ++k) {
        if (pinned_[k]) continue;
        a[k] = add(scale(1.0 / mass_[k], sub(f[k], scale(drag(int(k)), v[k]))), prm_.gravity);
    }
    return a;
}

void Simulation::pin(std::vector<V3>& x, std::vector<V3>& v) const {
    for (std::size_t k = 0; k < x.size(); ++k) {
        if (!pinned_[k]) continue;
        if (follow_[k] < 0) {
            x[k] = rest_[k];
            v[k] = {0, 0, 0};
            continue;
        }
        const Motion& m = prm_.colliders[follow_[k]].motion;
        x[k] = motionPoint(m, colliderTime_, rest_[k]);
        v[k] = motionVelocity(m, colliderTime_, x[k]);
    }
}

// DESIGN.md §2, order inside one step: pins reset, then the colliders in scene order.
void Simulation::pinAndCollide(std::vector<V3>& x, std::vector<V3>& v) const {
    pin(x, v);
    for (std::size_t k = 0; k < x.size(); ++k) applyColliders(x[k], v[k]);
}

void Simulation::step() {
    colliderTime_ = double(steps_ + 1) * prm_.dt;
    switch (prm_.method) {
        case Method::ExplicitEuler:
            stepExplicitEuler();
            break;
        case Method::SymplecticEuler:
            stepSymplecticEuler();
            break;
        case Method::Verlet:
            stepVerlet();
            break;
        case Method::Rk4:
            stepRk4();
            break;
        case Method::ImplicitEuler:
            stepImplicitEuler();
            break;
        case Method::BackwardEuler:
            stepBackwardEuler();
            break;
    }
    ++steps_;
}

double Simulation::kineticEnergy(const std::vector<V3>& v) const {
    double e = 0;
    for (std::size_t k = 0; k < v.size(); ++k) e += 0.5 * mass_[k] * dot(v[k], v[k]);
    return e;
}

double Simulation::springEnergy(const std::vector<V3>& p) const {
    double e = 0;
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) {
            for (const Offset& o : kHalfOffsets) {
                const double k = stiffness(i, j, o.di, o.dj, o.family);
                const int qi = i + o.di, qj = j + o.dj;
                if (k == 0 || qi < 0 || qi >= prm_.nu || qj < 0 || qj >= prm_.nv) continue;
                const double stretch =
                    norm(sub(p[qj * prm_.nu + qi], p[j * prm_.nu + i])) - restLength(o.di, o.dj);
                e += 0.5 * k * stretch * stretch;
            }
        }
    }
    return e;
}

double Simulation::gravityEnergy(const std::vector<V3>& p) const {
    double e = 0;
    for (std::size_t k = 0; k < p.size(); ++k) e -= mass_[k] * dot(prm_.gravity, p[k]);
    return e;
}

double Simulation::kineticEnergy() const {
    return kineticEnergy(v_);
}
double Simulation::springEnergy() const {
    return springEnergy(p_);
}
double Simulation::gravityEnergy() const {
    return gravityEnergy(p_);
}

bool Simulation::finiteAndBelowMaxSpeed() const {
    for (std::size_t k = 0; k < p_.size(); ++k) {
        for (int c = 0; c < 3; ++c) {
            if (!std::isfinite(p_[k][c]) || !std::isfinite(v_[k][c])) return false;
        }
        if (norm(v_[k]) > prm_.maxSpeed) return false;
    }
    return true;
}

}  // namespace ref
