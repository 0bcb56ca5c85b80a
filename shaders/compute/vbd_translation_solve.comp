// vbd, the translation's step (docs/integrators.md "vbd", few sweeps; src/cpu/
// cpu_vbd_translation.cpp vbdTranslate): one work group sums the grid's partial sums and takes
// the Newton step t = −H⁻¹g (vbdNewtonStep, floor Σ m/h²) into vbdTranslation[0].
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#ifdef HAS_BENDING
#define BENDING_FIELD(q) positions[vertexIndex(q)].xyz
#include "bending.glsl"
#endif
#include "vbd_local.glsl"

layout(local_size_x = 256) in;

#include "reduction.glsl"

void main() {
    uint groups = uint((gridU() + WX - 1) / WX) * uint((gridV() + WY - 1) / WY);
    vec4 s[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
    for (uint g = gl_LocalInvocationIndex; g < groups; g += gl_WorkGroupSize.x)
        for (uint e = 0u; e < 3u; ++e) s[e] += vbdTranslation[1u + 3u * g + e];
    for (int e = 0; e < 12; ++e) {
        s[e / 4][e % 4] = workGroupSum(s[e / 4][e % 4]);
        barrier();  // groupSums is reused
    }
    if (gl_LocalInvocationIndex != 0u) return;
    VbdLocal l = VbdLocal(s[0].xyz, s[1].xyz, s[2].xyz);
    vec3 t;
    bool step = vbdNewtonStep(l, s[0].w, t);
    vbdTranslation[0] = step ? vec4(t, 1.0) : vec4(0.0);
}
