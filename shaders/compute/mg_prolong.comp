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
    int cu = levelU(c);
    int I, J;
    double wu, wv;
    interpolationRow(ij.x, levelU(l), cu, I, wu);
    interpolationRow(ij.y, levelV(l), levelV(c), J, wv);
    dvec3 sum = dvec3(0.0lf);
    for (int b = 0; b < 2; ++b) {
        double wj = b == 0 ? 1.0lf - wv : wv;
        if (wj == 0.0lf) continue;
        for (int a = 0; a < 2; ++a) {
            double wi = a == 0 ? 1.0lf - wu : wu;
            if (wi == 0.0lf) continue;
            sum += (wi * wj) * loadVector(c, (J + b) * cu + I + a, kMgZ);
        }
    }
    storeVector(l, k, kMgZ, loadVector(l, k, kMgZ) + sum);
}
