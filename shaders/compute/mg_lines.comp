// implicit_euler's multigrid preconditioner: the line smoother's factors of level uLevel
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp smoother): every row (direction 0) and column (1)
// of the grid as one banded system of 3 unknowns a vertex, the stencil's blocks along the line,
// factored A_line = L Lᵀ in place. One invocation per line (one a work group: each factor is
// sequential, and separate groups spread over the device), the rows first.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 64) in;

void main() {
    int l = uLevel, nu = levelU(l), nv = levelV(l);
    int id = int(gl_GlobalInvocationID.x);
    if (id >= nu + nv) return;
    int direction = id < nv ? 0 : 1, line = id < nv ? id : id - nv;
    int m = lineLength(l, direction), dofs = 3 * m;
    int f = lineAt(l, direction, line);
    for (int e = 0; e < dofs * (kMgBand + 1); ++e) mgWork[f + e] = 0.0lf;
    for (int a = 0; a < m; ++a) {  // A's lower band: blocks (a, b), b = a − 2 … a
        ivec2 ij = onLine(direction, line, a);
        int k = ij.y * nu + ij.x;
        for (int b = max(0, a - 2); b <= a; ++b) {
            int d = b - a;
            dmat3 block = loadBlock(blockAt(l, k, direction == 0 ? stencilSlot(d, 0) : stencilSlot(0, d)));
            for (int row = 0; row < 3; ++row)
                for (int col = 0; col < 3; ++col) {
                    int R = 3 * a + row, C = 3 * b + col;
                    if (C <= R) mgWork[bandAt(f, R, C)] = blockEntry(block, row, col);
                }
        }
    }
    for (int i = 0; i < dofs; ++i) {  // banded Cholesky in place
        int lo = max(0, i - kMgBand);
        double diagonal = mgWork[bandAt(f, i, i)];
        for (int j = lo; j <= i; ++j) {
            double s = mgWork[bandAt(f, i, j)];
            for (int q = lo; q < j; ++q)
                if (j - q <= kMgBand) s -= mgWork[bandAt(f, i, q)] * mgWork[bandAt(f, j, q)];
            // A pivot at or under float's rounding of the stiff blocks is held at 1e-6 of the
            // diagonal, as on the CPU.
            mgWork[bandAt(f, i, j)] = i == j ? squareRoot(max(s, 1e-6lf * diagonal + 1e-300lf))
                                             : divide(s, mgWork[bandAt(f, j, j)]);
        }
    }
}
