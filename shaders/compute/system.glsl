// implicit_euler's matrix-vector product (docs/integrators.md), src/model/implicit_system.h's
// ImplicitSystem::apply: A w = m_k (1 + hc) w + h² H w (+ h D w with spring damping), a gather
// over the stencil at x_n, plus the grab's h² K w; pinned rows 0. The including kernel #defines
// STIFFNESS_VECTOR as the w it multiplies and includes grab.glsl and stiffness.glsl first. With
// contacts in the solve the row is filtered: S A w (solve_contact.glsl).
#include "solve_contact.glsl"
vec3 unfilteredSystemProduct(ivec2 ij, uint k) {
    float inverseMass = positions[k].w;
    if (inverseMass == 0.0) return vec3(0.0);
    vec3 w = STIFFNESS_VECTOR[k].xyz;
    float h = params.dt, h2 = h * h;
    float drag = 1.0 + h * params.dampingRate;
    // h² H w + h D w in one gather: h² (H w + D w / h).
    vec3 aw = (drag / inverseMass) * w + h2 * stiffnessProduct(ij, k, 1.0 / h);
    if (grabbed(k)) aw += h2 * uGrab.w * w;
    return aw;
}

vec3 systemProduct(ivec2 ij, uint k) { return filterContact(k, unfilteredSystemProduct(ij, k)); }
