// implicit_euler's multigrid preconditioner: level uLevel's system A_c = Pᵀ A P from the level
// above (multigrid.glsl; src/cpu/cpu_multigrid.cpp galerkin), one coarse vertex K per
// invocation: for every fine vertex k in a cell with corner K (block P_kK) and every block A_kq,
// the corners Q of q's cell get P_kKᵀ A_kq P_qQ. Pinned vertices of either grid take no part; a
// pinned coarse row is the identity's.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    int l = uLevel, f = l - 1;
    ivec2 IJ;
    int K;
    if (!levelVertex(l, IJ, K)) return;
    int nu = levelU(f), nv = levelV(f), cu = levelU(l), cv = levelV(l);
    dmat3 row[25];
    for (int o = 0; o < 25; ++o) row[o] = dmat3(0.0lf);
    if (pinnedAt(l, IJ)) {
        row[stencilSlot(0, 0)] = dmat3(1.0lf);
    } else {
        ivec2 cellsU = cellsOf(IJ.x, cu), cellsV = cellsOf(IJ.y, cv);
        for (int Cv = cellsV.x; Cv <= cellsV.y; ++Cv)
            for (int Cu = cellsU.x; Cu <= cellsU.y; ++Cu) {
                int corner = (IJ.x - Cu) + 2 * (IJ.y - Cv);
                ivec2 spanU = cellSpan(Cu, nu, cu), spanV = cellSpan(Cv, nv, cv);
                for (int j = spanV.x; j <= spanV.y; ++j)
                    for (int i = spanU.x; i <= spanU.y; ++i) {
                        if (pinnedAt(f, ivec2(i, j))) continue;
                        ivec2 cell;
                        dmat3 pk[4];
                        prolongationBlocks(l, ivec2(i, j), cell, pk);
                        if (pk[corner] == dmat3(0.0lf)) continue;
                        dmat3 pkT = transpose(pk[corner]);
                        int k = j * nu + i;
                        for (int dj = -2; dj <= 2; ++dj) {
                            int qj = j + dj;
                            if (qj < 0 || qj >= nv) continue;
                            for (int di = -2; di <= 2; ++di) {
                                int qi = i + di;
                                if (qi < 0 || qi >= nu || pinnedAt(f, ivec2(qi, qj)) ||
                                    !stencilReaches(f, di, dj))
                                    continue;
                                dmat3 m = pkT * loadBlock(blockAt(f, k, stencilSlot(di, dj)));
                                ivec2 cellQ;
                                dmat3 pq[4];
                                prolongationBlocks(l, ivec2(qi, qj), cellQ, pq);
                                for (int c = 0; c < 4; ++c) {
                                    ivec2 Q = cellQ + ivec2(c & 1, c >> 1);
                                    if (Q.x >= cu || Q.y >= cv || pq[c] == dmat3(0.0lf)) continue;
                                    if (pinnedAt(l, Q)) continue;
                                    ivec2 d = Q - IJ;  // within ±2: P keeps radius 2
                                    row[stencilSlot(d.x, d.y)] += m * pq[c];
                                }
                            }
                        }
                    }
            }
    }
    for (int o = 0; o < 25; ++o) storeBlock(blockAt(l, K, o), row[o]);
}
