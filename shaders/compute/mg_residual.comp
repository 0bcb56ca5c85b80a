// implicit_euler's multigrid preconditioner: t = r − A z on level uLevel (multigrid.glsl;
// src/cpu/cpu_multigrid.cpp cycle), before it is restricted to the next coarser grid.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, nu = levelU(l), nv = levelV(l);
    ivec2 ij;
    int k;
    if (!levelVertex(l, ij, k)) return;
    dvec3 sum = loadVector(l, k, kMgR);
    if (!pinnedAt(l, ij)) {
        for (int dj = max(-2, -ij.y); dj <= min(2, nv - 1 - ij.y); ++dj)
            for (int di = max(-2, -ij.x); di <= min(2, nu - 1 - ij.x); ++di)
                sum -= times(loadBlock(blockAt(l, k, stencilSlot(di, dj))),
                             loadVector(l, k + dj * nu + di, kMgZ));
    }
    storeVector(l, k, kMgT, sum);
}
