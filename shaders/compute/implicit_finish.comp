// implicit_euler's update after the solve (docs/integrators.md): v_{n+1} = v_n + Δv,
// x_{n+1} = x_n + h v_{n+1}, then pins, colliders and the instability check.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 vel = v.xyz + cgVelocityChange[k].xyz;
    finishStep(uStep, k, x, v, x.xyz + params.dt * vel, vel);
}
