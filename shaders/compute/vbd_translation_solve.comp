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

layout(local_size_x = 256) in;  // kGroup

const uint kGroup = 256u;
shared vec4 groupSums3[3][kGroup];

void main() {
    uint groups = uint((gridU() + WX - 1) / WX) * uint((gridV() + WY - 1) / WY);
    uint t = gl_LocalInvocationIndex;
    vec4 s[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
    for (uint g = t; g < groups; g += kGroup)
        for (uint e = 0u; e < 3u; ++e) s[e] += vbdTranslation[1u + 3u * g + e];
    for (uint e = 0u; e < 3u; ++e) groupSums3[e][t] = s[e];
    memoryBarrierShared();
    barrier();
    for (uint stride = kGroup / 2u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (uint e = 0u; e < 3u; ++e) groupSums3[e][t] += groupSums3[e][t + stride];
        memoryBarrierShared();
        barrier();
    }
    if (t != 0u) return;
    VbdLocal l = VbdLocal(groupSums3[0][0].xyz, groupSums3[1][0].xyz, groupSums3[2][0].xyz);
    vec3 step;
    bool taken = vbdNewtonStep(l, groupSums3[0][0].w, step);
    vbdTranslation[0] = taken ? vec4(step, 1.0) : vec4(0.0);
}
