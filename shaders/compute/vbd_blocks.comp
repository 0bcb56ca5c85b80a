// vbd, the translation's levels (integrator.translation_levels; docs/integrators.md "vbd"; src/
// cpu/cpu_vbd_translation.cpp vbdTranslateLevels): one work group a block of the sheet cut into
// uVbd.x × uVbd.x equal parts, the blocks of colour uVbd.y (block column parity, row parity ×
// 2). It sums the gradient and Hessian of G on the block's translation — its free vertices' own
// terms (vbd_translation.glsl) and their springs to vertices outside the block or pinned — takes
// the Newton step t and adds it to the block's free vertices, then the colliders' projection.
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#include "grab.glsl"
#include "step_end.glsl"
#ifdef HAS_BENDING
#define BENDING_FIELD(q) positions[vertexIndex(q)].xyz
#include "bending.glsl"
#endif
#include "vbd_local.glsl"
#include "vbd_translation.glsl"

layout(local_size_x = 256) in;  // kGroup
layout(location = 3) uniform ivec2 uVbd;  // (parts a side, colour)

const uint kGroup = 256u;
shared vec4 groupSums3[3][kGroup];

void main() {
    if (frozen(uStep)) return;
    int parts = uVbd.x, colour = uVbd.y;
    ivec2 b = 2 * ivec2(gl_WorkGroupID.xy) + ivec2(colour % 2, colour / 2);
    if (b.x >= parts || b.y >= parts) return;
    ivec2 lo = (b * ivec2(gridU(), gridV())) / parts;
    ivec2 hi = ((b + 1) * ivec2(gridU(), gridV())) / parts;
    int width = hi.x - lo.x, count = width * (hi.y - lo.y);
    uint t = gl_LocalInvocationIndex;
    VbdLocal l = vbdLocalZero();
    float inertia = 0.0;
    for (int v = int(t); v < count; v += int(kGroup)) {
        ivec2 ij = lo + ivec2(v % width, v / width);
        uint k = vertexIndex(ij);
        vec4 x4 = positions[k];
        if (x4.w == 0.0) continue;
        inertia += addVbdTranslationTerms(l, k, x4);
#if NUM_SPRING_OFFSETS > 0
        for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
            ivec4 s = kSpringOffsets[o];
            ivec2 q = ij + s.xy;
            if (!insideGrid(q)) continue;
            vec4 xq = positions[vertexIndex(q)];
            if (all(greaterThanEqual(q, lo)) && all(lessThan(q, hi)) && xq.w != 0.0) continue;
            addVbdSpring(l, x4.xyz, xq.xyz, springStiffnessAt(s, ij), springRestLength(s));
        }
#endif
    }
    groupSums3[0][t] = vec4(l.gradient, inertia);
    groupSums3[1][t] = vec4(l.diagonal, 0.0);
    groupSums3[2][t] = vec4(l.offDiagonal, 0.0);
    memoryBarrierShared();
    barrier();
    for (uint stride = kGroup / 2u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (uint e = 0u; e < 3u; ++e) groupSums3[e][t] += groupSums3[e][t + stride];
        memoryBarrierShared();
        barrier();
    }
    VbdLocal sum = VbdLocal(groupSums3[0][0].xyz, groupSums3[1][0].xyz, groupSums3[2][0].xyz);
    float floorInertia = groupSums3[0][0].w;
    vec3 step;
    if (!(floorInertia > 0.0) || !vbdNewtonStep(sum, floorInertia, step)) return;
    for (int v = int(t); v < count; v += int(kGroup)) {
        ivec2 ij = lo + ivec2(v % width, v / width);
        uint k = vertexIndex(ij);
        vec4 x4 = positions[k];
        if (x4.w == 0.0) continue;
        vec3 x = x4.xyz + step, d = vbdDisplacement[k].xyz + step;
#ifdef HAS_COLLIDERS
        vec3 p = x, vel = vec3(0.0);
        applyColliders(uStep, p, vel);
        d += p - x;
        x = p;
#endif
        positions[k] = vec4(x, x4.w);
        vbdDisplacement[k] = vec4(d, 0.0);
    }
}
