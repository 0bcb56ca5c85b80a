// vbd, the Chebyshev extrapolation after a sweep (docs/integrators.md "vbd", the paper's §3.8;
// src/cpu/cpu_vbd.cpp vbdAccelerate): d ← ω (d − d^(n−2)) + d^(n−2) on the free vertices, the
// position moved by as much, then the colliders' projection alone (vbdProject: no friction, the
// contacts kept), which moves both.
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
    vec3 d = vbdDisplacement[k].xyz;
    if (uVbd > 1.0) {
        vec3 last = vbdBeforeLast[k].xyz, now = d;
        d = uVbd * (now - last) + last;
        vec3 x = x4.xyz + (d - now);
#ifdef HAS_COLLIDERS
        vec3 p = x, vel = vec3(0.0);
        applyColliders(uStep, p, vel);
        d += p - x;
        x = p;
#endif
        positions[k] = vec4(x, x4.w);
        vbdDisplacement[k] = vec4(d, 0.0);
    }
    vbdBeforeLast[k] = vbdBefore[k];
    vbdBefore[k] = vec4(d, 0.0);
}
