// implicit_euler's update after the solve (docs/integrators.md): v_{n+1} = v_n + Δv,
// x_{n+1} = x_n + h v_{n+1}, then pins, colliders and the instability check. With contacts in the
// solve a contact keeps no normal velocity away from its surface faster than the surface moves
// (src/model/solve_contact.h contactVelocity): a vertex that started inside leaves at rest.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"
#include "solve_contact.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 vel = v.xyz + cgVelocityChange[k].xyz, end = x.xyz + params.dt * vel;
#ifdef HAS_SOLVE_CONTACTS
    vec3 n = cgContacts[3u * k].xyz;
    if (n != vec3(0.0)) {
        float h = params.dt;
        vec3 pStar = x.xyz + h * (v.xyz + h * params.gravity);
        float away = dot(n, vel - colliderSurfaceVelocity(uStep, pStar));
        if (away > 0.0) vel -= away * n;
    }
#endif
    finishStep(uStep, k, x, v, end, vel);
}
