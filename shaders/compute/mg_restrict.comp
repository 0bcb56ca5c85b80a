// implicit_euler's multigrid preconditioner: r_c = Pᵀ t on level uLevel from the level above,
// and z_c = 0, the coarse cycle's start (multigrid.glsl; src/cpu/cpu_multigrid.cpp cycle). 0 on
// pinned coarse vertices; t is 0 on pinned fine ones.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, f = l - 1;
    ivec2 IJ;
    int K;
    if (!levelVertex(l, IJ, K)) return;
    int nu = levelU(f), nv = levelV(f), cu = levelU(l), cv = levelV(l);
    dvec3 sum = dvec3(0.0lf);
    if (!pinnedAt(l, IJ)) {
        ivec2 cellsU = cellsOf(IJ.x, cu), cellsV = cellsOf(IJ.y, cv);
        for (int Cv = cellsV.x; Cv <= cellsV.y; ++Cv)
            for (int Cu = cellsU.x; Cu <= cellsU.y; ++Cu) {
                int corner = (IJ.x - Cu) + 2 * (IJ.y - Cv);
                ivec2 spanU = cellSpan(Cu, nu, cu), spanV = cellSpan(Cv, nv, cv);
                for (int j = spanV.x; j <= spanV.y; ++j)
                    for (int i = spanU.x; i <= spanU.y; ++i) {
                        ivec2 cell;
                        dmat3 p[4];
                        prolongationBlocks(l, ivec2(i, j), cell, p);
                        sum += loadVector(f, j * nu + i, kMgT) * p[corner];  // P_kKᵀ t_k
                    }
            }
    }
    storeVector(l, K, kMgR, sum);
    storeVector(l, K, kMgZ, dvec3(0.0lf));
}
