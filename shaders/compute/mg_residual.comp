// implicit_euler's multigrid preconditioner: t = r − A z on level uLevel (multigrid.glsl;
// src/cpu/cpu_multigrid.cpp cycle), before it is restricted to the next coarser grid.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = uLevel;
    ivec2 ij;
    int k;
    if (!levelVertex(l, ij, k)) return;
    storeVector(l, k, kMgT, residualAt(l, ij, k, -1));  // r is 0 on pinned vertices
}
