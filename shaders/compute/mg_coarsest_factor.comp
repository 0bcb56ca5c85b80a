// implicit_euler's multigrid preconditioner: the coarsest grid's system as a dense matrix (pinned
// rows and columns the identity's) factored A = L Lᵀ in double by one work group
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp factorCoarsest): column by column, each entry of
// the column by its own invocation, which reads the entries others wrote: the work buffer is
// coherent here.
#define MG_WORK_COHERENT coherent
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 64) in;

void main() {
    int l = MG_LEVEL_COUNT - 1, nu = levelU(l), nv = levelV(l), n = nu * nv, dofs = 3 * n;
    int a = coarsestFirst();
    uint t = gl_LocalInvocationIndex, threads = gl_WorkGroupSize.x;
    for (int e = int(t); e < dofs * dofs; e += int(threads)) mgWork[a + e] = 0.0lf;
    memoryBarrierBuffer();
    barrier();
    for (int k = int(t); k < n; k += int(threads)) {
        int i = k % nu, j = k / nu;
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
                if (i + di < 0 || i + di >= nu || j + dj < 0 || j + dj >= nv) continue;
                int q = k + dj * nu + di;
                dmat3 b = loadBlock(blockAt(l, k, stencilSlot(di, dj)));
                for (int row = 0; row < 3; ++row)
                    for (int col = 0; col < 3; ++col)
                        mgWork[a + (3 * k + row) * dofs + 3 * q + col] = blockEntry(b, row, col);
            }
    }
    memoryBarrierBuffer();
    barrier();
    for (int j = 0; j < dofs; ++j) {  // Cholesky–Banachiewicz, the lower triangle in place
        if (t == 0u) {
            double s = mgWork[a + j * dofs + j], diagonal = s;
            for (int m = 0; m < j; ++m) s -= mgWork[a + j * dofs + m] * mgWork[a + j * dofs + m];
            mgWork[a + j * dofs + j] = squareRoot(max(s, 1e-6lf * diagonal + 1e-300lf));
        }
        memoryBarrierBuffer();
        barrier();
        for (int i = j + 1 + int(t); i < dofs; i += int(threads)) {
            double s = mgWork[a + i * dofs + j];
            for (int m = 0; m < j; ++m) s -= mgWork[a + i * dofs + m] * mgWork[a + j * dofs + m];
            mgWork[a + i * dofs + j] = divide(s, mgWork[a + j * dofs + j]);
        }
        memoryBarrierBuffer();
        barrier();
    }
}
