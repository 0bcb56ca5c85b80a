// implicit_euler's multigrid preconditioner: z += P z_c on level uLevel from the next coarser
// one, on unpinned vertices (multigrid.glsl; src/cpu/cpu_multigrid.cpp cycle).
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, c = l + 1;
    ivec2 ij;
    int k;
    if (!levelVertex(l, ij, k) || pinnedAt(l, ij)) return;
    int cu = levelU(c), cv = levelV(c);
    ivec2 cell;
    dmat3 p[4];
    prolongationBlocks(c, ij, cell, p);
    dvec3 sum = dvec3(0.0lf);
    for (int corner = 0; corner < 4; ++corner) {
        ivec2 Q = cell + ivec2(corner & 1, corner >> 1);
        if (Q.x >= cu || Q.y >= cv) continue;
        sum += p[corner] * loadVector(c, Q.y * cu + Q.x, kMgZ);
    }
    storeVector(l, k, kMgZ, loadVector(l, k, kMgZ) + sum);
}
