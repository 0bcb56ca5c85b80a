// Pass 2 of explicit_euler and symplectic_euler (DESIGN.md §2 "Order inside one step", §3,
// docs/integrators.md): integrate, reset pins, apply the colliders in scene order, and flag the
// first step at which anything went bad.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"
#include "euler_step.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    integrateVertex(uStep, vertexIndex(ij));
}
