// implicit_euler, after the forces pass (docs/integrators.md): the right-hand side
// b = h (F(x_n) + m_k (g − c v_n) − h H v_n) of (m_k (1 + hc) I + h D + h² H) Δv = b into
// cgResidual, the work groups' partial sums of b·b and of s·s (s the sum of the magnitudes of
// b's terms), the last solution Δv₀ held 0 on pinned rows
// (the warm start's product reads it next), and with PRECONDITIONER_JACOBI the inverted diagonal
// blocks of A. Pinned rows are 0. With contacts in the solve (solve_contact.glsl) also each
// vertex's contact, predicted through the colliders at the end of step uStep, and the friction's
// impulse in b.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR velocities
#include "stiffness.glsl"
#include "solve_contact.glsl"
#ifdef HAS_SOLVE_CONTACTS
layout(location = 2) uniform uint uStep;
#include "scene_colliders.glsl"

#include "coulomb.glsl"

// The contact of a free vertex of mass m at (x, v) (src/model/solve_contact.h predictContact):
// the prediction p* = x + h v*, v* = v + h g through the colliders; pushed out by d ≠ 0,
// n = d/|d| and z = ⟨n, p' − x⟩/h − ⟨n, v⟩, and by the grip of the last step either the hold
// (held) or the friction (sliding, new) and whether it stuck, into cgContacts. Returns the
// friction's velocity change.
vec3 predictContact(uint k, vec3 x, vec3 v, float m) {
    float h = params.dt, grip = cgContacts[3u * k + 1u].w;
    vec3 vStar = v + h * params.gravity, pStar = x + h * vStar;
    vec3 p = pStar, w = vStar;
    applyColliders(uStep, p, w);
    vec3 d = p - pStar;
    float len = length(d);
    cgContacts[3u * k] = vec4(0.0);
    cgContacts[3u * k + 1u] = vec4(0.0);
    cgContacts[3u * k + 2u] = vec4(0.0);
    if (!(len > 0.0)) return vec3(0.0);
    vec3 n = d / len;
    float z = dot(n, p - x) / h - dot(n, v);
    cgContacts[3u * k] = vec4(n, z);
    vec3 slide = vStar - n * dot(n, vStar), vc = colliderSurfaceVelocity(uStep, pStar);
    vec3 still = vc - n * dot(n, vc);
    if (grip < 0.0) {
        cgContacts[3u * k + 1u] = vec4(still - (v - n * dot(n, v)), grip);
        return vec3(0.0);
    }
    vec3 kept = grip > 0.0 ? coulomb(pStar, n, slide, grip / m) : w - n * dot(n, w);
    // Held next where the response took its static branch (v_c exactly) and the vertex did not
    // already move with the surface.
    bool stuck = kept == still && slide != still;
    cgContacts[3u * k + 1u] = vec4(0.0, 0.0, 0.0, grip);
    cgContacts[3u * k + 2u].w = stuck ? 1.0 : 0.0;
    return kept - slide;
}
#endif

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

#ifdef PRECONDITIONER_JACOBI
// A_kk⁻¹ of a vertex of mass m (ImplicitSystem::diagonal), or 0 for a pinned one.
void storeInverse(ivec2 ij, uint k, float inverseMass) {
    vec4 d = vec4(0.0), o = vec4(0.0);
    if (inverseMass != 0.0) {
        float h = params.dt;
        mat3 a = mat3((1.0 + h * params.dampingRate) / inverseMass) +
                 (h * h) * stiffnessDiagonal(ij, k, 1.0 / h);
        if (grabbed(k)) a += mat3(h * h * uGrab.w);
        mat3 inv = inverse(a);
        d = vec4(inv[0][0], inv[1][1], inv[2][2], 0.0);
        o = vec4(inv[1][0], inv[2][0], inv[2][1], 0.0);
    }
    cgInverse[2u * k] = d;
    cgInverse[2u * k + 1u] = o;
}
#endif

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float bb = 0.0, ss = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {  // no early return: every invocation sums below
        uint k = vertexIndex(ij);
        vec4 x = positions[k];
        vec3 v = velocities[k].xyz;
        vec3 hv = stiffnessProduct(ij, k);
        if (grabbed(k)) hv += uGrab.w * v;
        float h = params.dt;
        vec3 b = vec3(0.0);  // a pinned row (x.w = 0)
        if (x.w != 0.0) {
            float m = 1.0 / x.w;  // m_k [kg]
            b = h * (forces[k].xyz + m * (params.gravity - params.dampingRate * v) - h * hv);
#ifdef HAS_SOLVE_CONTACTS
            b += m * predictContact(k, x.xyz, v, m);
            cgContacts[3u * k + 2u].xyz = b;
#endif
        } else {
            cgVelocityChange[k] = vec4(0.0);  // a new pin: the last solution moved it
#ifdef HAS_SOLVE_CONTACTS
            for (uint c = 0u; c < 3u; ++c) cgContacts[3u * k + c] = vec4(0.0);
#endif
        }
        cgResidual[k] = vec4(b, 0.0);
        bb = dot(b, b);
        // The magnitudes of b's terms: the stopping test's floor (cg_reduce.comp).
        if (x.w != 0.0) {
            float s = h * (length(forces[k].xyz) +
                           length(params.gravity - params.dampingRate * v) / x.w +
                           h * length(hv)) +
                      length(b);
            ss = s * s;
        }
#ifdef PRECONDITIONER_JACOBI
        storeInverse(ij, k, x.w);
#endif
    }
    storeGroupSums(bb, ss);
}
