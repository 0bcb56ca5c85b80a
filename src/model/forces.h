// Stateless physics of DESIGN.md §2: positions and parameters in, force or normal out. The GLSL
// kernels in shaders/compute/common.glsl mirror these function for function.
#pragma once

#include <algorithm>
#include <cmath>

#include "model/grid.h"
#include "model/spring_math.h"
#include "model/sym3.h"

namespace cloth {

// Force on vertex k from the spring to q (seed eq. (2)): F = K (|d| − L) d/|d|, d = p_q − p_k.
// A spring squeezed to (almost) zero length has no direction and adds nothing.
template <typename T>
Vec3<T> springForce(const Vec3<T>& pk, const Vec3<T>& pq, T stiffness, T restLength) {
    const Vec3<T> d = pq - pk;
    return springCoefficient(d.x, d.y, d.z, stiffness, restLength) * d;
}

// Damping of the spring from k to q added to f (spring_math.h addSpringDamping): w = v_q − v_k,
// dampingK = βK [N·s/m].
template <typename T>
void addSpringDamping(const Vec3<T>& pk, const Vec3<T>& pq, const Vec3<T>& w, T dampingK,
                      T restLength, Vec3<T>& f) {
    const Vec3<T> d = pq - pk;
    addSpringDamping(d.x, d.y, d.z, w.x, w.y, w.z, dampingK, restLength, f.x, f.y, f.z);
}

// J_s w for the spring from k to q, J_s = ∂F_k/∂x_q its 3×3 Jacobian with the compressive part
// clamped (docs/integrators.md, implicit_euler): J_s = K (d̂d̂ᵀ + max(0, 1 − L/l)(I − d̂d̂ᵀ)).
// Positive semi-definite; 0 where the spring force is (a spring squeezed to a point).
template <typename T>
Vec3<T> springJacobianTimes(const Vec3<T>& pk, const Vec3<T>& pq, T stiffness, T restLength,
                            const Vec3<T>& w) {
    const Vec3<T> d = pq - pk;
    const T len = glm::length(d);
    if (!(len >= T(1e-12) * restLength)) return Vec3<T>(0);
    const Vec3<T> n = d / len;
    const T transverse = stiffness * std::max(T(0), T(1) - restLength / len);
    return transverse * w + ((stiffness - transverse) * glm::dot(n, w)) * n;
}

// J_s itself, the block springJacobianTimes applies: the diagonal blocks of implicit Euler's
// system (its preconditioners) sum them.
template <typename T>
Sym3<T> springJacobian(const Vec3<T>& pk, const Vec3<T>& pq, T stiffness, T restLength) {
    const Vec3<T> d = pq - pk;
    const T len = glm::length(d);
    if (!(len >= T(1e-12) * restLength)) return {};
    const T transverse = stiffness * std::max(T(0), T(1) - restLength / len);
    return Sym3<T>::identity(transverse) += Sym3<T>::outer(d / len, stiffness - transverse);
}

// −∂F_β/∂v_k of the damping of the spring from k to q (addSpringDamping): βK d̂d̂ᵀ, 0 where
// the spring is squeezed below 1e-12 L.
template <typename T>
Sym3<T> springDampingBlock(const Vec3<T>& pk, const Vec3<T>& pq, T dampingK, T restLength) {
    const Vec3<T> d = pq - pk;
    const T d2 = glm::dot(d, d), floor = T(1e-12) * restLength;
    return d2 >= floor * floor ? Sym3<T>::outer(d, dampingK / d2) : Sym3<T>{};
}

// Unit vertex normal from central differences clamped at the border (DESIGN.md §2);
// 0 where the cross product vanishes, so 1-D chains have no normal and feel no wind.
template <typename T, typename PositionAt>
Vec3<T> vertexNormal(int nu, int nv, int i, int j, const PositionAt& p) {
    const Vec3<T> a = p(std::min(i + 1, nu - 1), j) - p(std::max(i - 1, 0), j);
    const Vec3<T> b = p(i, std::min(j + 1, nv - 1)) - p(i, std::max(j - 1, 0));
    Vec3<T> n;
    unitNormal(a.x, a.y, a.z, b.x, b.y, b.z, n.x, n.y, n.z);
    return n;
}

// Wind (seed §5.3): F_w = K_w ⟨n, û_w⟩ n.
template <typename T>
Vec3<T> windForce(const Vec3<T>& normal, const Vec3<T>& direction, T strength) {
    return (strength * glm::dot(normal, direction)) * normal;  // spring_math.h addWind, as a value
}

// The user's grab: a spring of rest length 0 from the vertex to a target point, F = K (t − x).
template <typename T>
Vec3<T> grabForce(const Vec3<T>& position, const Vec3<T>& target, T stiffness) {
    return stiffness * (target - position);
}

}  // namespace cloth
