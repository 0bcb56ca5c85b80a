// vbd, the Chebyshev extrapolation after a sweep (docs/integrators.md "vbd", the paper's §3.8;
// src/cpu/cpu_vbd.cpp vbdAccelerate): x ← ω (x − x^(n−2)) + x^(n−2) on the free vertices, then
// the colliders' projection as after a Newton step.
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
        float h = params.dt;
        vec3 xn = vbdStart[k].xyz, before = (x - xn) / h, p = x, vel = before;
        applyColliders(uStep, p, vel);
        vec3 push = p - x;
        float pushed = length(push);
        if (pushed > 0.0) {
            vec3 n = push / pushed, lost = before - vel;
            x = p - h * (lost - dot(lost, n) * n);
        }
#endif
        positions[k] = vec4(x, x4.w);
    }
    vbdBeforeLast[k] = vbdBefore[k];
    vbdBefore[k] = vec4(x, 0.0);
}
