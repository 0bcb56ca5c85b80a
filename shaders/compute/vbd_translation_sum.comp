// vbd, the translation's sums (docs/integrators.md "vbd", few sweeps; src/cpu/
// cpu_vbd_translation.cpp vbdTranslationRow): each invocation's part of the gradient and Hessian
// of G on the rigid translation of the free vertices — a free vertex's inertia, drag, friction
// and contact hold (10⁴ m/h² along the push of its last Newton step's projection), a pinned
// vertex's springs to free neighbours, the grabbed vertex's grab — summed over the work group
// into its three vec4 of vbdTranslation.
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

layout(local_size_x = WX, local_size_y = WY) in;

// The three vec4 of sums, reduced together: one tree in shared memory for all ten.
shared vec4 groupSums3[3][WX * WY];

#include "vbd_translation.glsl"

VbdLocal translationTerms(ivec2 ij, out float inertia) {
    VbdLocal l = vbdLocalZero();
    inertia = 0.0;
    uint k = vertexIndex(ij);
    vec4 x4 = positions[k];
    if (x4.w == 0.0) {  // pinned: its springs to free vertices, seen from them
#if NUM_SPRING_OFFSETS > 0
        for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
            ivec4 s = kSpringOffsets[o];
            ivec2 q = ij + s.xy;
            if (!insideGrid(q)) continue;
            vec4 xq = positions[vertexIndex(q)];
            if (xq.w == 0.0) continue;
            addVbdSpring(l, xq.xyz, x4.xyz, springStiffnessAt(s, ij), springRestLength(s));
        }
#endif
        return l;
    }
    inertia = addVbdTranslationTerms(l, k, x4);
    return l;
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    VbdLocal l = vbdLocalZero();
    float inertia = 0.0;
    if (ij.x < gridU() && ij.y < gridV() && !frozen(uStep)) l = translationTerms(ij, inertia);
    uint t = gl_LocalInvocationIndex, n = uint(WX * WY);
    groupSums3[0][t] = vec4(l.gradient, inertia);
    groupSums3[1][t] = vec4(l.diagonal, 0.0);
    groupSums3[2][t] = vec4(l.offDiagonal, 0.0);
    memoryBarrierShared();
    barrier();
    uint stride = 1u;
    while (2u * stride < n) stride *= 2u;
    for (; stride > 0u; stride >>= 1) {
        if (t < stride && t + stride < n)
            for (int e = 0; e < 3; ++e) groupSums3[e][t] += groupSums3[e][t + stride];
        memoryBarrierShared();
        barrier();
    }
    if (t != 0u) return;
    uint at = 1u + 3u * (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x);
    for (uint e = 0u; e < 3u; ++e) vbdTranslation[at + e] = groupSums3[e][0];
}
