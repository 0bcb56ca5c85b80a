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
