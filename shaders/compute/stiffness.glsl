// The stiffness operator H = −∂F/∂x of the spring forces, applied without storing it: one gather
// over the 12-neighbour stencil, like the force pass (docs/integrators.md, implicit_euler).
// Mirrors src/model/stiffness.h. The including kernel #defines STIFFNESS_VECTOR as the array H
// multiplies: velocities for the right-hand side, cgDirection for A p.
#include "springs.glsl"
#ifdef HAS_BENDING
#define BENDING_FIELD(q) STIFFNESS_VECTOR[vertexIndex(q)].xyz
#include "bending.glsl"
#endif

// (H w)_k + c (D w)_k: H the stiffness, Σ_s J_s(x) (w_k − w_q) over the springs of vertex k,
// J_s clamped (springJacobianTimes) at the positions x; D = −∂F/∂v = Σ_s βK d̂d̂ᵀ the spring
// damping's (docs/integrators.md), read in the same gather under HAS_SPRING_DAMPING, weighted by
// c = dampingWeight. The row of a pinned vertex is 0: a pin is a constraint, not a degree of
// freedom; the solve keeps w = 0 there, which removes its column.
vec3 stiffnessProduct(ivec2 ij, uint k, float dampingWeight) {
    vec3 y = vec3(0.0);
    if (positions[k].w == 0.0) return y;
#if NUM_SPRING_OFFSETS > 0
    vec3 xk = positions[k].xyz;
    vec3 wk = STIFFNESS_VECTOR[k].xyz;
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        uint kq = vertexIndex(q);
        vec3 xq = positions[kq].xyz, wq = STIFFNESS_VECTOR[kq].xyz;
        y += springJacobianTimes(xk, xq, springStiffnessAt(s, ij), springRestLength(s), wk - wq);
#ifdef HAS_SPRING_DAMPING
        y -= dampingWeight *
             springDampingForce(xq - xk, wq - wk, springDampingAt(s, ij), springRestLength(s));
#endif
    }
#endif
#ifdef HAS_BENDING
    y -= bendingForce(ij, params.bending.xyz);  // the bending Hessian is constant: H_b w = −F_b(w)
#endif
    return y;
}

// (H w)_k alone.
vec3 stiffnessProduct(ivec2 ij, uint k) { return stiffnessProduct(ij, k, 0.0); }

#ifdef PRECONDITIONER_JACOBI
// The diagonal block H_kk + c D_kk of vertex k (not pinned), src/model/implicit_system.h
// ImplicitSystem::diagonal: each spring's clamped J_s = tI + (K − t) d̂d̂ᵀ, its damping βK d̂d̂ᵀ
// weighted by c = dampingWeight, and the bending Hessian's diagonal coefficient.
mat3 stiffnessDiagonal(ivec2 ij, uint k, float dampingWeight) {
    mat3 a = mat3(0.0);
#if NUM_SPRING_OFFSETS > 0
    vec3 xk = positions[k].xyz;
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        vec3 d = positions[vertexIndex(q)].xyz - xk;
        float len = length(d), restLength = springRestLength(s);
        if (!(len >= 1e-12 * restLength)) continue;
        vec3 n = d / len;
        float stiffness = springStiffnessAt(s, ij);
        float transverse = stiffness * max(0.0, 1.0 - restLength / len);
        float along = stiffness - transverse;
#ifdef HAS_SPRING_DAMPING
        along += dampingWeight * springDampingAt(s, ij);
#endif
        a += mat3(transverse) + along * outerProduct(n, n);
    }
#endif
#ifdef HAS_BENDING
    a += mat3(bendingDiagonal(ij, params.bending.xyz));
#endif
    return a;
}
#endif
