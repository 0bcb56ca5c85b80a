// verlet, second half (docs/integrators.md): the kick with F_{n+1} = F(x_{n+1}), which stays in
// the forces buffer as the next step's F(x_n); then pins and the instability check. Colliders
// acted after the drift and do not act again.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 p = x.xyz;
    vec3 vel = kick(v.xyz, forces[k].xyz, x.w, params.dt, params.dampingRate, params.gravity);
    applyPin(uStep, x, v, p, vel);
    velocities[k] = vec4(vel, v.w);
    checkStability(uStep, k, p, vel);
}
