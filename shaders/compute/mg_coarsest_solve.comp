// implicit_euler's multigrid preconditioner: z = (L Lᵀ)⁻¹ r on the coarsest grid by its dense
// factor (multigrid.glsl; src/cpu/cpu_multigrid.cpp solveCoarsest), 0 on pinned vertices; its r
// and z are the level's vectors. One invocation: a few hundred unknowns.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 1) in;

void main() {
    if (cg.done != 0u) return;
    int l = MG_LEVEL_COUNT - 1, nu = levelU(l), n = nu * levelV(l), dofs = 3 * n;
    int a = coarsestFirst(), r = vectorAt(l, 0, kMgR), z = vectorAt(l, 0, kMgZ);
    // y and z in z's entries: vertex k's component c at z + 9 k + c.
    for (int i = 0; i < dofs; ++i) {  // L y = r
        double s = mgWork[r + 9 * (i / 3) + i % 3];
        for (int m = 0; m < i; ++m) s -= mgWork[a + i * dofs + m] * mgWork[z + 9 * (m / 3) + m % 3];
        mgWork[z + 9 * (i / 3) + i % 3] = divide(s, mgWork[a + i * dofs + i]);
    }
    for (int i = dofs - 1; i >= 0; --i) {  // Lᵀ z = y
        double s = mgWork[z + 9 * (i / 3) + i % 3];
        for (int m = i + 1; m < dofs; ++m) s -= mgWork[a + m * dofs + i] * mgWork[z + 9 * (m / 3) + m % 3];
        mgWork[z + 9 * (i / 3) + i % 3] = divide(s, mgWork[a + i * dofs + i]);
    }
    for (int k = 0; k < n; ++k)
        if (pinnedAt(l, ivec2(k % nu, k / nu))) storeVector(l, k, kMgZ, dvec3(0.0lf));
}
