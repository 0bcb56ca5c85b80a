// implicit_euler's multigrid preconditioner: the line factors' chunk transfers on level uLevel,
// once a step after mg_lines.comp (multigrid.glsl transferAt; mg_relax.comp uses them). For
// chunk [a, b) of a line, the forward substitution's transfer is how its last 8 rows move with
// the 8 rows before it, the back substitution's how its first 8 rows move with the 8 rows after
// it: each column, the chunk substituted with no right-hand side from one row set to 1. One work
// group a line (every row, then every column), one invocation a chunk.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"
#include "mg_chunks.glsl"

layout(local_size_x = MG_CHUNKS) in;

void main() {
    int l = uLevel, nu = levelU(l), nv = levelV(l);
    int id = int(gl_WorkGroupID.x);
    if (id >= nu + nv) return;
    int direction = id < nv ? 0 : 1, line = id < nv ? id : id - nv;
    int m = lineLength(l, direction), dofs = 3 * m;
    int chunks = chunkCount(m), p = int(gl_LocalInvocationID.x);
    if (chunks == 1 || p >= chunks) return;
    int f = lineAt(l, direction, line);
    int a = p * 3 * chunkVertices(m), b = min(a + 3 * chunkVertices(m), dofs);
    int transfer = transferAt(l, direction, line, p);
    for (int u = 0; u < kMgBand; ++u) {
        double recent[kMgBand];  // newest first: row a − 1 − c forward, row b + c back
        for (int c = 0; c < kMgBand; ++c) recent[c] = kMgBand - 1 - c == u ? 1.0lf : 0.0lf;
        forwardChunk(l, direction, line, f, a, b, false, false, recent);
        for (int t = 0; t < kMgBand; ++t) mgWork[transfer + t * kMgBand + u] = recent[kMgBand - 1 - t];
        for (int c = 0; c < kMgBand; ++c) recent[c] = c == u ? 1.0lf : 0.0lf;
        backwardChunk(l, direction, line, f, dofs, a, b, false, false, recent);
        for (int t = 0; t < kMgBand; ++t) mgWork[transfer + 64 + t * kMgBand + u] = recent[t];
    }
}
