// vbd's end of step (docs/integrators.md "vbd"): v_{n+1} = (x − x_n)/h, then pins, colliders and
// the instability check.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    finishStep(uStep, k, x, v, x.xyz, (x.xyz - vbdStart[k].xyz) / params.dt);
}
