// implicit_euler with contacts in the solve, after it (src/model/solve_contact.h nextGrip): each
// contact's impulse J = (A Δv)_k − b_k (A Δv unfiltered, b_k from the right-hand side's pass)
// sets its grip for the next step. J_n ≤ 0 lets go; a held contact stays held while the
// colliders' Coulomb law with J_n supplies its tangential impulse J_t, and slides with J_n
// otherwise; a sliding one is held once its friction stopped it.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR cgVelocityChange
#include "stiffness.glsl"
#include "system.glsl"

layout(location = 2) uniform uint uStep;
#include "scene_colliders.glsl"
#include "coulomb.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

float nextGrip(ivec2 ij, uint k) {
    vec4 c = cgContacts[3u * k], hold = cgContacts[3u * k + 1u], load = cgContacts[3u * k + 2u];
    vec3 n = c.xyz;
    if (n == vec3(0.0)) return 0.0;
    vec3 impulse = unfilteredSystemProduct(ij, k) - load.xyz;
    float jn = dot(n, impulse);
    if (!(jn > 0.0)) return 0.0;  // the collider would pull: let go
    if (!(hold.w < 0.0)) return load.w != 0.0 ? -jn : jn;
    vec4 x = positions[k];
    vec3 v = velocities[k].xyz;
    float h = params.dt;
    vec3 jt = (impulse - n * jn) * x.w;  // J_t / m
    vec3 free = v - n * dot(n, v) + hold.xyz - jt;
    vec3 kept = coulomb(x.xyz + h * (v + h * params.gravity), n, free, jn * x.w);
    return length(kept - free) >= 0.999 * length(jt) ? -jn : jn;
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;
    uint k = vertexIndex(ij);
    cgContacts[3u * k + 1u].w = positions[k].w == 0.0 ? 0.0 : nextGrip(ij, k);
}
