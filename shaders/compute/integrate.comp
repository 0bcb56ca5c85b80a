// Pass 2 of explicit_euler and symplectic_euler (DESIGN.md §2 "Order inside one step", §3,
// docs/integrators.md): integrate, reset pins, apply the colliders in scene order, and flag the
// first step at which anything went bad.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen()) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 p = x.xyz, vel = v.xyz;
    integrate(p, vel, forces[k].xyz, x.w, params.integration.x, params.gravity.w,
              params.gravity.xyz);
    finishStep(k, x, v, p, vel);
}
