// vbd, the translation's step applied (docs/integrators.md "vbd", few sweeps; src/cpu/
// cpu_vbd_translation.cpp vbdTranslate): t added to every free vertex's position and
// displacement, then the colliders' projection alone, as after Chebyshev's extrapolation.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    vec4 t = vbdTranslation[0];
    uint k = vertexIndex(ij);
    vec4 x4 = positions[k];
    if (x4.w == 0.0 || t.w == 0.0) return;
    vec3 x = x4.xyz + t.xyz, d = vbdDisplacement[k].xyz + t.xyz;
#ifdef HAS_COLLIDERS
    vec3 p = x, vel = vec3(0.0);
    applyColliders(uStep, p, vel);
    d += p - x;
    x = p;
#endif
    positions[k] = vec4(x, x4.w);
    vbdDisplacement[k] = vec4(d, 0.0);
}
