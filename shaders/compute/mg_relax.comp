// implicit_euler's multigrid preconditioner, line Gauss–Seidel's second half on level uLevel
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp relaxLine): lines uLine.y, uLine.y + 5, … in
// direction uLine.x, one per invocation, each solved exactly, A_line z_line = t, with its banded
// factor (t the right-hand side mg_relax_right_hand_side.comp left). Lines of one colour lie 5
// apart, outside each other's stencil, so they are solved independently. One invocation a work
// group: each line is a sequential substitution, and separate groups spread over the device.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 64) in;

int lineEntry(int l, int direction, int line, int i, int which) {
    ivec2 ij = onLine(direction, line, i / 3);
    return vectorAt(l, ij.y * levelU(l) + ij.x, which) + i % 3;
}

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, direction = uLine.x;
    int line = uLine.y + 5 * int(gl_GlobalInvocationID.x);
    if (line >= (direction == 0 ? levelV(l) : levelU(l))) return;
    int dofs = 3 * lineLength(l, direction);
    int f = lineAt(l, direction, line);
    for (int i = 0; i < dofs; ++i) {  // L y' = t
        double s = mgWork[lineEntry(l, direction, line, i, kMgT)];
        for (int q = max(0, i - kMgBand); q < i; ++q)
            s -= mgWork[bandAt(f, i, q)] * mgWork[lineEntry(l, direction, line, q, kMgZ)];
        mgWork[lineEntry(l, direction, line, i, kMgZ)] = divide(s, mgWork[bandAt(f, i, i)]);
    }
    for (int i = dofs - 1; i >= 0; --i) {  // Lᵀ z = y'
        double s = mgWork[lineEntry(l, direction, line, i, kMgZ)];
        for (int q = i + 1; q < min(dofs, i + kMgBand + 1); ++q)
            s -= mgWork[bandAt(f, q, i)] * mgWork[lineEntry(l, direction, line, q, kMgZ)];
        mgWork[lineEntry(l, direction, line, i, kMgZ)] = divide(s, mgWork[bandAt(f, i, i)]);
    }
    for (int a = 0; a < lineLength(l, direction); ++a) {
        ivec2 ij = onLine(direction, line, a);
        if (pinnedAt(l, ij)) storeVector(l, ij.y * levelU(l) + ij.x, kMgZ, dvec3(0.0lf));
    }
}
