// vbd, the translation's levels (integrator.translation_levels; docs/integrators.md "vbd"; src/
// cpu/cpu_vbd_translation.cpp vbdTranslateLevels): the blocks of colour uVbd.y (block column
// parity, row parity × 2) of the sheet cut into uVbd.x × uVbd.x equal parts. A block's problem
// sums its free vertices' own terms (vbd_translation.glsl) and their springs to vertices outside
// the block or pinned; its Newton step t is added to the block's free vertices, then the
// colliders' projection. uVbd.w says which part of that this dispatch does:
// - 0: all of it, one work group a block;
// - 1: the sums of one of a block's uVbd.z chunks a work group, into vbdTranslation;
// - 3: one work group a chunk sums its block's chunks' sums, takes the block's step (every
//   work group of the block the same, in the same order) and applies it to its chunk;
// - 4: all of it, one invocation a block.
// Chunks let the first levels' few large blocks spread over many work groups; the last levels'
// many small blocks take an invocation each, without the work group's barriers.
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
layout(location = 3) uniform ivec4 uVbd;  // (parts a side, colour, chunks a block, mode)

const uint kGroup = 256u;
shared vec4 groupSums3[3][kGroup];

// Block b of the colour's (parts/2)² blocks: its vertices [lo, hi).
void blockBounds(int b, out ivec2 lo, out ivec2 hi) {
    int parts = uVbd.x, colour = uVbd.y, across = parts / 2;
    ivec2 at = 2 * ivec2(b % across, b / across) + ivec2(colour % 2, colour / 2);
    lo = (at * ivec2(gridU(), gridV())) / parts;
    hi = ((at + 1) * ivec2(gridU(), gridV())) / parts;
}

// The sums of the block's vertices first, first + stride, … below last (block-local, row by
// row) into l and inertia.
void sumBlock(ivec2 lo, ivec2 hi, int first, int last, int stride, inout VbdLocal l,
              inout float inertia) {
    int width = hi.x - lo.x;
    for (int v = first; v < last; v += stride) {
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
}

void reduceGroup() {
    uint t = gl_LocalInvocationIndex;
    memoryBarrierShared();
    barrier();
    for (uint stride = kGroup / 2u; stride > 0u; stride >>= 1) {
        if (t < stride)
            for (uint e = 0u; e < 3u; ++e) groupSums3[e][t] += groupSums3[e][t + stride];
        memoryBarrierShared();
        barrier();
    }
}

// The work group's sums of the block's vertices [first, last) into groupSums3[·][0].
void sumBlockInGroup(ivec2 lo, ivec2 hi, int first, int last) {
    uint t = gl_LocalInvocationIndex;
    VbdLocal l = vbdLocalZero();
    float inertia = 0.0;
    sumBlock(lo, hi, first + int(t), last, int(kGroup), l, inertia);
    groupSums3[0][t] = vec4(l.gradient, inertia);
    groupSums3[1][t] = vec4(l.diagonal, 0.0);
    groupSums3[2][t] = vec4(l.offDiagonal, 0.0);
    reduceGroup();
}


// The Newton step of the sums: (t, 1), or 0 where none is taken.
vec4 blockStep(VbdLocal sum, float floorInertia) {
    vec3 step;
    if (!(floorInertia > 0.0) || !vbdNewtonStep(sum, floorInertia, step)) return vec4(0.0);
    return vec4(step, 1.0);
}

vec4 groupStep() {
    VbdLocal sum = VbdLocal(groupSums3[0][0].xyz, groupSums3[1][0].xyz, groupSums3[2][0].xyz);
    return blockStep(sum, groupSums3[0][0].w);
}

// The step on the block's vertices first, first + stride, … below last.
void applyBlock(ivec2 lo, ivec2 hi, int first, int last, int stride, vec4 step) {
    if (step.w == 0.0) return;
    int width = hi.x - lo.x;
    for (int v = first; v < last; v += stride) {
        ivec2 ij = lo + ivec2(v % width, v / width);
        uint k = vertexIndex(ij);
        vec4 x4 = positions[k];
        if (x4.w == 0.0) continue;
        vec3 x = x4.xyz + step.xyz, d = vbdDisplacement[k].xyz + step.xyz;
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

void main() {
    if (frozen(uStep)) return;
    int chunks = uVbd.z, mode = uVbd.w, group = int(gl_WorkGroupID.x);
    int across = uVbd.x / 2, blocks = across * across;
    if (mode == 4) {
        int block = int(gl_GlobalInvocationID.x);
        if (block >= blocks) return;
        ivec2 lo, hi;
        blockBounds(block, lo, hi);
        VbdLocal l = vbdLocalZero();
        float inertia = 0.0;
        int count = (hi.x - lo.x) * (hi.y - lo.y);
        sumBlock(lo, hi, 0, count, 1, l, inertia);
        applyBlock(lo, hi, 0, count, 1, blockStep(l, inertia));
        return;
    }
    int block = mode == 0 ? group : group / chunks, chunk = group % chunks;
    ivec2 lo, hi;
    blockBounds(block, lo, hi);
    int count = (hi.x - lo.x) * (hi.y - lo.y);
    int first = mode == 0 ? 0 : (chunk * count) / chunks;
    int last = mode == 0 ? count : ((chunk + 1) * count) / chunks;
    uint at = 1u + 3u * uint(group);  // mode 1: this chunk's sums
    uint t = gl_LocalInvocationIndex;
    if (mode == 0 || mode == 1) {
        sumBlockInGroup(lo, hi, first, last);
        if (mode == 0) {
            applyBlock(lo, hi, first + int(t), last, int(kGroup), groupStep());
        } else if (gl_LocalInvocationIndex == 0u) {
            for (uint e = 0u; e < 3u; ++e) vbdTranslation[at + e] = groupSums3[e][0];
        }
    } else {  // 3: the block's chunks' sums (at most kGroup of them), in a fixed order
        for (uint e = 0u; e < 3u; ++e)
            groupSums3[e][t] = int(t) < chunks
                                   ? vbdTranslation[1u + 3u * uint(block * chunks + int(t)) + e]
                                   : vec4(0.0);
        reduceGroup();
        applyBlock(lo, hi, first + int(t), last, int(kGroup), groupStep());
    }
}
