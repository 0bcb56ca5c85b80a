// implicit_euler's multigrid preconditioner: level uLevel's system A_c = Pᵀ A P from the level
// above (multigrid.glsl; src/cpu/cpu_multigrid.cpp galerkin), one coarse vertex K per
// invocation: for every fine vertex k that K gathers (weight w_K) and every block A_kq, the
// coarse vertices Q that q interpolates from (weight w_Q) get w_K w_Q A_kq. Pinned vertices of
// either grid take no part; a pinned coarse row is the identity's.
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
    Sym3 row[25];
    for (int o = 0; o < 25; ++o) row[o] = Sym3(0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf, 0.0lf);
    if (pinnedAt(l, IJ)) {
        row[stencilSlot(0, 0)] = Sym3(1.0lf, 0.0lf, 0.0lf, 1.0lf, 0.0lf, 1.0lf);
    } else {
        ivec2 spanU = interpolationSpan(IJ.x, nu, cu), spanV = interpolationSpan(IJ.y, nv, cv);
        for (int j = spanV.x; j <= spanV.y; ++j) {
            double wj = interpolationWeight(IJ.y, j, nv, cv);
            for (int i = spanU.x; i <= spanU.y; ++i) {
                double wi = interpolationWeight(IJ.x, i, nu, cu);
                if (wi * wj == 0.0lf || pinnedAt(f, ivec2(i, j))) continue;
                int k = j * nu + i;
                for (int dj = -2; dj <= 2; ++dj) {
                    int qj = j + dj;
                    if (qj < 0 || qj >= nv) continue;
                    int Qj;
                    double vq;
                    interpolationRow(qj, nv, cv, Qj, vq);
                    for (int di = -2; di <= 2; ++di) {
                        int qi = i + di;
                        if (qi < 0 || qi >= nu) continue;
                        Sym3 b = loadBlock(blockAt(f, k, stencilSlot(di, dj)));
                        int Qi;
                        double uq;
                        interpolationRow(qi, nu, cu, Qi, uq);
                        // P's row of q: (Qi, Qj) with (1 − uq)(1 − vq), and so on.
                        for (int c = 0; c < 4; ++c) {
                            int ai = c & 1, aj = c >> 1;
                            double w = (ai == 0 ? 1.0lf - uq : uq) * (aj == 0 ? 1.0lf - vq : vq);
                            if (w == 0.0lf) continue;
                            ivec2 Q = ivec2(Qi + ai, Qj + aj);
                            if (pinnedAt(l, Q)) continue;
                            ivec2 d = Q - IJ;  // within ±2: bilinear P keeps radius 2
                            double s = wi * wj * w;
                            Sym3 r = row[stencilSlot(d.x, d.y)];
                            r.xx += s * b.xx;
                            r.xy += s * b.xy;
                            r.xz += s * b.xz;
                            r.yy += s * b.yy;
                            r.yz += s * b.yz;
                            r.zz += s * b.zz;
                            row[stencilSlot(d.x, d.y)] = r;
                        }
                    }
                }
            }
        }
    }
    for (int o = 0; o < 25; ++o) storeBlock(blockAt(l, K, o), row[o]);
}
