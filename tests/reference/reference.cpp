// The reference model, DESIGN.md §2, written out as directly as possible.
#include "reference/reference.h"

#include <cmath>

namespace ref {
namespace {

V3 add(const V3& a, const V3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V3 sub(const V3& a, const V3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
V3 scale(double s, const V3& a) {
    return {s * a[0], s * a[1], s * a[2]};
}
double dot(const V3& a, const V3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const V3& a) {
    return std::sqrt(dot(a, a));
}
V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 normalised(const V3& a) {
    return scale(1.0 / norm(a), a);
}

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
    pinned_.assign(n, false);
    for (const auto& pin : prm_.pins) {
        const int i = resolve(pin[0], prm_.nu), j = resolve(pin[1], prm_.nv);
        pinned_[j * prm_.nu + i] = true;
    }
    p_.resize(n);
    v_.assign(n, V3{0, 0, 0});
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) p_[j * prm_.nu + i] = restPosition(i, j);
    }
}

V3 Simulation::restPosition(int i, int j) const {
    return add(prm_.origin, add(scale(i * du_, u_), scale(j * dv_, vAxis_)));
}

double Simulation::stiffness(int family) const {
    return family == 0 ? prm_.kStructural : family == 1 ? prm_.kShear : prm_.kBend;
}

double Simulation::restLength(int di, int dj) const {
    return norm(add(scale(di * du_, u_), scale(dj * dv_, vAxis_)));
}

// Σ over existing neighbours of K (|d| − L) d/|d|, d = p_q − p_k (seed eq. (2)).
V3 Simulation::springForces(int i, int j) const {
    V3 f{0, 0, 0};
    const V3& pk = p_[j * prm_.nu + i];
    for (const Offset& o : kOffsets) {
        const double k = stiffness(o.family);
        const int qi = i + o.di, qj = j + o.dj;
        if (k == 0 || qi < 0 || qi >= prm_.nu || qj < 0 || qj >= prm_.nv) continue;
        const double len = restLength(o.di, o.dj);
        const V3 d = sub(p_[qj * prm_.nu + qi], pk);
        const double dist = norm(d);
        if (dist < 1e-12 * len) continue;
        f = add(f, scale(k * (dist - len) / dist, d));
    }
    return f;
}

// K_w ⟨n, û_w⟩ n with the central-difference vertex normal of §2 (seed §5.3).
V3 Simulation::windForce(int i, int j) const {
    const int nu = prm_.nu, nv = prm_.nv;
    const int ip = i + 1 < nu - 1 ? i + 1 : nu - 1, im = i - 1 > 0 ? i - 1 : 0;
    const int jp = j + 1 < nv - 1 ? j + 1 : nv - 1, jm = j - 1 > 0 ? j - 1 : 0;
    const V3 a = sub(p_[j * nu + ip], p_[j * nu + im]);
    const V3 b = sub(p_[jp * nu + i], p_[jm * nu + i]);
    const V3 axb = cross(a, b);
    const double len = norm(axb);
    if (len < 1e-12) return {0, 0, 0};
    const V3 n = scale(1.0 / len, axb);
    return scale(prm_.windStrength * dot(n, wind_), n);
}

// Plane (Q12): project onto it and cancel the normal velocity. Sphere (Q13): push to the surface
// and cancel the radial velocity. In the order the scene lists them.
void Simulation::applyColliders(V3& p, V3& v) const {
    for (const Collider& c : prm_.colliders) {
        if (!c.isSphere) {
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
}

// DESIGN.md §2: forces from the state at t → explicit Euler (seed eq. (6), old velocity for the
// position) → pins reset → colliders.
void Simulation::step() {
    const int nu = prm_.nu, nv = prm_.nv;
    std::vector<V3> force(p_.size());
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            V3 f = springForces(i, j);
            if (prm_.wind) f = add(f, windForce(i, j));
            force[j * nu + i] = f;
        }
    }
    const double dt = prm_.dt, m = prm_.mass, mu = prm_.damping;
    for (int j = 0; j < nv; ++j) {
        for (int i = 0; i < nu; ++i) {
            const int k = j * nu + i;
            const V3 vOld = v_[k];
            const V3 a = add(scale(1.0 / m, sub(force[k], scale(mu, vOld))), prm_.gravity);
            v_[k] = add(vOld, scale(dt, a));
            p_[k] = add(p_[k], scale(dt, vOld));
            if (pinned_[k]) {
                p_[k] = restPosition(i, j);
                v_[k] = {0, 0, 0};
            }
            applyColliders(p_[k], v_[k]);
        }
    }
    ++steps_;
}

double Simulation::kineticEnergy(const std::vector<V3>& v) const {
    double e = 0;
    for (const V3& x : v) e += 0.5 * prm_.mass * dot(x, x);
    return e;
}

double Simulation::springEnergy(const std::vector<V3>& p) const {
    double e = 0;
    for (int j = 0; j < prm_.nv; ++j) {
        for (int i = 0; i < prm_.nu; ++i) {
            for (const Offset& o : kHalfOffsets) {
                const double k = stiffness(o.family);
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
    for (const V3& x : p) e -= prm_.mass * dot(prm_.gravity, x);
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
