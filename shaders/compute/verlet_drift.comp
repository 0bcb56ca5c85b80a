// verlet, first half (docs/integrators.md): kick with a(x_n, v_n), drift to x_{n+1}, then pins
// and colliders act on (x_{n+1}, v_half). The forces pass then evaluates F(x_{n+1}).
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 p = x.xyz, vel = v.xyz;
    kickAndDrift(p, vel, forces[k].xyz, x.w, params.dt, params.dampingRate, params.gravity);
    applyPin(uStep, x, v, p, vel);
#ifdef HAS_COLLIDERS
    applyColliders(uStep, p, vel);
#endif
    positions[k] = vec4(p, x.w);
    velocities[k] = vec4(vel, v.w);
}
