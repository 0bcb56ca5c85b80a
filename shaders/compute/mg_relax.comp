// implicit_euler's multigrid preconditioner, line Gauss–Seidel's second half on level
// lineLevel() (multigrid.glsl; src/cpu/cpu_multigrid.cpp substitutePairs): lines c, c + 5, … of
// colour c = lineColour() in lineDirection(), one per work group, each solved exactly,
// A_line z_line = t, with its banded factor (t the right-hand side mg_relax_right_hand_side.comp
// left). Lines of one colour lie 5 apart, outside each other's stencil, so they are solved
// independently. With MG_CHUNKS 1 a line is one chain and a work group takes 64 lines.
//
// A substitution is a chain of dependent rows. Along a line of 3 m rows it ran at one row's
// latency a row; here each invocation takes one chunk of the line (multigrid.glsl
// chunkVertices), so a chain is a chunk long. Each substitution runs in three parts:
//   1. every chunk substitutes as if the rows before it were 0 (its last 8 rows' values kept);
//   2. the 8 rows that enter each chunk follow chunk by chunk: those of chunk p + 1 are chunk
//      p's last 8 as found in 1, plus chunk p's transfer (mg_line_transfers.comp) times those
//      that enter chunk p — 8 invocations, one an entry, a chunk a step;
//   3. every chunk substitutes again from the rows that enter it: the line's exact solution, up
//      to rounding (the sequential solve's result in other rounding).
// The back substitution runs the same way from the line's end.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"
#include "mg_chunks.glsl"

layout(local_size_x = MG_RELAX_GROUP) in;

shared double transfers[MG_CHUNKS * 64];  // the chunks' transfers of the substitution running
shared double ends[MG_CHUNKS * kMgBand];  // each chunk's 8 rows next to its neighbour, from 1
shared double enter[MG_CHUNKS * kMgBand];  // the 8 rows that enter each chunk, from 2

void sync() {
    memoryBarrierShared();
    barrier();
}

void main() {
    if (cg.done != 0u) return;
    int l = lineLevel(), direction = lineDirection();
    int line = lineColour() + 5 * int(gl_GlobalInvocationID.x / MG_CHUNKS);
    if (line >= (direction == 0 ? levelV(l) : levelU(l))) return;
    int m = lineLength(l, direction), dofs = 3 * m;
    int f = lineAt(l, direction, line);
    int chunks = chunkCount(m), p = int(gl_LocalInvocationID.x) % MG_CHUNKS;
    bool mine = p < chunks;
    int a = min(p * 3 * chunkVertices(m), dofs), b = min(a + 3 * chunkVertices(m), dofs);
    int transfer = transferAt(l, direction, line, min(p, chunks - 1));
    double recent[kMgBand];  // y of the rows before the row forward, z of those after it back
    for (int c = 0; c < kMgBand; ++c) recent[c] = 0.0lf;
    if (chunks == 1) {  // one chunk: the line's own substitutions (no barrier: lines may end early)
        if (mine) {
            forwardChunk(l, direction, line, f, a, b, true, true, recent);
            for (int c = 0; c < kMgBand; ++c) recent[c] = 0.0lf;
            backwardChunk(l, direction, line, f, dofs, a, b, true, true, recent);
        }
    } else {
        // L y' = t.
        if (mine) {
            forwardChunk(l, direction, line, f, a, b, true, false, recent);
            for (int t = 0; t < kMgBand; ++t) ends[p * kMgBand + t] = recent[kMgBand - 1 - t];
            for (int e = 0; e < 64; ++e) transfers[p * 64 + e] = mgWork[transfer + e];
        }
        if (p < kMgBand) enter[p] = 0.0lf;  // nothing enters the first chunk
        sync();
        for (int q = 0; q + 1 < chunks; ++q) {
            if (p < kMgBand) {
                double s = ends[q * kMgBand + p];
                for (int u = 0; u < kMgBand; ++u)
                    s += transfers[q * 64 + p * kMgBand + u] * enter[q * kMgBand + u];
                enter[(q + 1) * kMgBand + p] = s;
            }
            sync();
        }
        if (mine) {
            for (int c = 0; c < kMgBand; ++c) recent[c] = enter[p * kMgBand + kMgBand - 1 - c];
            forwardChunk(l, direction, line, f, a, b, true, true, recent);
        }
        sync();  // every chunk has read `enter`
        // Lᵀ z = y'.
        for (int c = 0; c < kMgBand; ++c) recent[c] = 0.0lf;
        if (mine) {
            backwardChunk(l, direction, line, f, dofs, a, b, true, false, recent);
            for (int t = 0; t < kMgBand; ++t) ends[p * kMgBand + t] = recent[t];
            for (int e = 0; e < 64; ++e) transfers[p * 64 + e] = mgWork[transfer + 64 + e];
        }
        if (p < kMgBand) enter[(chunks - 1) * kMgBand + p] = 0.0lf;  // nothing enters the last
        sync();
        for (int q = chunks - 1; q > 0; --q) {
            if (p < kMgBand) {
                double s = ends[q * kMgBand + p];
                for (int u = 0; u < kMgBand; ++u)
                    s += transfers[q * 64 + p * kMgBand + u] * enter[q * kMgBand + u];
                enter[(q - 1) * kMgBand + p] = s;
            }
            sync();
        }
        if (mine) {
            for (int c = 0; c < kMgBand; ++c) recent[c] = enter[p * kMgBand + c];
            backwardChunk(l, direction, line, f, dofs, a, b, true, true, recent);
        }
    }
    if (!mine) return;
    for (int v = a / 3; v < b / 3; ++v) {
        ivec2 ij = onLine(direction, line, v);
        if (pinnedAt(l, ij)) storeVector(l, ij.y * levelU(l) + ij.x, kMgZ, dvec3(0.0lf));
    }
}
