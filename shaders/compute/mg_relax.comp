// implicit_euler's multigrid preconditioner: one colour of line Gauss–Seidel on level uLevel
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp relaxLine): lines uLine.y, uLine.y + 5, … in
// direction uLine.x, one per invocation, each solved exactly, A_line z_line = r − (A z −
// A_line z_line), with its banded factor. Lines of one colour lie 5 apart, outside each other's
// stencil: the right-hand side reads z on other colours' lines only, so it is built in z's own
// entries of the line and solved there.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 64) in;

double lineValue(int l, int direction, int line, int i) {
    ivec2 ij = onLine(direction, line, i / 3);
    return mgWork[vectorAt(l, ij.y * levelU(l) + ij.x, kMgZ) + i % 3];
}
void setLineValue(int l, int direction, int line, int i, double value) {
    ivec2 ij = onLine(direction, line, i / 3);
    mgWork[vectorAt(l, ij.y * levelU(l) + ij.x, kMgZ) + i % 3] = value;
}

void main() {
    if (cg.done != 0u) return;  // the solve has converged (or stopped): no preconditioning
    int l = uLevel, nu = levelU(l), nv = levelV(l), direction = uLine.x;
    int line = uLine.y + 5 * int(gl_GlobalInvocationID.x);
    if (line >= (direction == 0 ? nv : nu)) return;
    int m = lineLength(l, direction), dofs = 3 * m;
    for (int a = 0; a < m; ++a) {
        ivec2 ij = onLine(direction, line, a);
        int k = ij.y * nu + ij.x;
        dvec3 sum = dvec3(0.0lf);
        if (!pinnedAt(l, ij)) {
            sum = loadVector(l, k, kMgR);
            for (int dj = max(-2, -ij.y); dj <= min(2, nv - 1 - ij.y); ++dj)
                for (int di = max(-2, -ij.x); di <= min(2, nu - 1 - ij.x); ++di) {
                    if (direction == 0 ? dj == 0 : di == 0) continue;  // on the line
                    sum -= times(loadBlock(blockAt(l, k, stencilSlot(di, dj))),
                                 loadVector(l, k + dj * nu + di, kMgZ));
                }
        }
        storeVector(l, k, kMgZ, sum);
    }
    int f = lineAt(l, direction, line);
    for (int i = 0; i < dofs; ++i) {  // L y' = y
        double s = lineValue(l, direction, line, i);
        for (int q = max(0, i - kMgBand); q < i; ++q)
            s -= mgWork[bandAt(f, i, q)] * lineValue(l, direction, line, q);
        setLineValue(l, direction, line, i, s / mgWork[bandAt(f, i, i)]);
    }
    for (int i = dofs - 1; i >= 0; --i) {  // Lᵀ z = y'
        double s = lineValue(l, direction, line, i);
        for (int q = i + 1; q < min(dofs, i + kMgBand + 1); ++q)
            s -= mgWork[bandAt(f, q, i)] * lineValue(l, direction, line, q);
        setLineValue(l, direction, line, i, s / mgWork[bandAt(f, i, i)]);
    }
    for (int a = 0; a < m; ++a) {
        ivec2 ij = onLine(direction, line, a);
        if (pinnedAt(l, ij)) storeVector(l, ij.y * nu + ij.x, kMgZ, dvec3(0.0lf));
    }
}
