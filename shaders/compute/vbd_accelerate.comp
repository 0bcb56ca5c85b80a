// vbd, the Chebyshev extrapolation after a sweep (docs/integrators.md "vbd", the paper's §3.8;
// src/cpu/cpu_vbd.cpp vbdAccelerate): x ← ω (x − x^(n−2)) + x^(n−2) on the free vertices, then
// the colliders' projection alone (vbdProject: no friction, the contacts kept).
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

layout(location = 3) uniform float uVbd;  // ω_n

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x4 = positions[k];
    if (x4.w == 0.0) return;
    vec3 x = x4.xyz;
    if (uVbd > 1.0) {
        vec3 last = vbdBeforeLast[k].xyz;
        x = uVbd * (x - last) + last;
#ifdef HAS_COLLIDERS
        vec3 vel = vec3(0.0);
        applyColliders(uStep, x, vel);
#endif
        positions[k] = vec4(x, x4.w);
    }
    vbdBeforeLast[k] = vbdBefore[k];
    vbdBefore[k] = vec4(x, 0.0);
}
