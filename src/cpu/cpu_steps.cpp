// One step of the explicit integrators (docs/integrators.md) on a band of rows: explicit and
// symplectic Euler (fused into the force sweep where they can be), velocity Verlet and RK4, and
// the dispatch on the method. Implicit Euler is in cpu_implicit.cpp, Vertex Block Descent in
// cpu_vbd.cpp, the force pass in cpu_forces.cpp.
#include <cstddef>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"

namespace cloth {

template <typename T>
bool CpuSolver<T>::advance(Band& band, const Team& team, long stepNumber, bool& haveForces) {
    switch (method_) {
        case Method::ExplicitEuler:
            return stepEuler(band, team, false);
        case Method::SymplecticEuler:
            return stepEuler(band, team, true);
        case Method::Verlet:
            return stepVerlet(band, team, haveForces);
        case Method::Rk4:
            return stepRk4(band, team);
        case Method::ImplicitEuler:
            return stepImplicit(band, team, stepNumber);
        case Method::Vbd:
            return stepVbd(band, team, stepNumber);
    }
    return false;
}

// explicit_euler, the seed's scheme (DESIGN.md §2, seed eq. (6)): x moves with the old
// velocity. symplectic_euler: with the new one.
template <typename T>
bool CpuSolver<T>::stepEuler(Band& band, const Team& team, bool symplectic) {
    if (fused()) return stepEulerFused(band, symplectic);
    gatherForcesScalar(band.begin, band.end);
    team.sync();
    const T h = dt_t_;
    const auto update = symplectic ? eulerComponent<T, true> : eulerComponent<T, false>;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        Vec3<T> p = x_.get(k), v = v_.get(k);
        const Vec3<T> f = f_.get(k);  // the row kernels' update, one vertex at a time
        const T w = inverseMass_[std::size_t(k)];
        for (int c = 0; c < 3; ++c) update(p[c], v[c], f[c], h, dampingRate_, w, gravity_[c]);
        if (!finishStep(band, k, p, v)) return false;
    }
    return true;
}

// Velocity Verlet, kick–drift–kick, the second kick's damping taken at v_{n+1} (trapezoidal):
// v_{n+1} = (v_half + h/2 (F_{n+1}/m_k + g)) / (1 + hc/2). F_{n+1} stays in f_ for the next step.
template <typename T>
bool CpuSolver<T>::stepVerlet(Band& band, const Team& team, bool& haveForces) {
    if (!haveForces) {
        gatherForces(band);
        team.sync();
    }
    const T h = dt_t_, half = T(0.5) * dt_t_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {  // kick and drift
        const Vec3<T> v0 = v_.get(k);
        Vec3<T> v = v0 + half * acceleration(k, v0);
        Vec3<T> p = x_.get(k) + h * v;
        constrain(k, p, v);
    }
    team.sync();
    gatherForces(band);  // F(x_{n+1}); the kick reads only its own vertex
    // ... but spring damping's gather reads the neighbours' v_half, which the kick overwrites.
    if (features_.springDamping) team.sync();
    haveForces = true;
    bool ok = true;
    const T denominator = T(1) + half * dampingRate_;
    for (std::int64_t k = band.begin; k < band.end && ok; ++k) {  // kick
        const T w = inverseMass_[std::size_t(k)];
        Vec3<T> v = (v_.get(k) + half * (f_.get(k) * w + gravity_)) / denominator;
        if (pinned_[k]) v = pinVelocity(k);
        v_.set(k, v);
        const Vec3<T> p = x_.get(k);
        if (badVertex(p.x, p.y, p.z, v.x, v.y, v.z, maxSpeed2_))
            ok = finishStep(band, k, p, v);  // reports it (pins and colliders are no-ops now)
    }
    return ok;
}

// Classic RK4 on y = (x, v): stage s evaluates f at the stage state in x_, v_; the start
// (x0_, v0_) and the sums k1 + 2k2 + 2k3 (sumX_, sumV_) carry across the stages.
template <typename T>
bool CpuSolver<T>::stepRk4(Band& band, const Team& team) {
    const T h = dt_t_, half = T(0.5) * dt_t_, sixth = dt_t_ / T(6);
    for (int stage = 0; stage < 4; ++stage) {
        gatherForces(band);
        team.sync();
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            const Vec3<T> v = v_.get(k);
            const Vec3<T> a = acceleration(k, v);
            if (stage == 0) {
                x0_[k] = x_.get(k);
                v0_[k] = v;
                sumX_[k] = v;
                sumV_[k] = a;
            } else if (stage < 3) {
                sumX_[k] += T(2) * v;
                sumV_[k] += T(2) * a;
            }
            if (stage == 3) {
                if (!finishStep(band, k, x0_[k] + sixth * (sumX_[k] + v),
                                v0_[k] + sixth * (sumV_[k] + a)))
                    return false;
                continue;
            }
            const T c = stage == 2 ? h : half;  // the next stage's point: y_n + c k
            if (pinned_[k]) {  // at the end of the step's pose (follow pins) in every stage
                x_.set(k, pinPosition_[k]);
                v_.set(k, pinVelocity(k));
            } else {
                x_.set(k, x0_[k] + c * v);
                v_.set(k, v0_[k] + c * a);
            }
        }
        if (stage < 3) team.sync();
    }
    return true;
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                              \
    template bool CpuSolver<T>::advance(Band&, const Team&, long, bool&); \
    template bool CpuSolver<T>::stepEuler(Band&, const Team&, bool);      \
    template bool CpuSolver<T>::stepVerlet(Band&, const Team&, bool&);    \
    template bool CpuSolver<T>::stepRk4(Band&, const Team&);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
