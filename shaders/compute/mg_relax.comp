// implicit_euler's multigrid preconditioner, line Gauss–Seidel's second half on level uLevel
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp relaxLine): lines uLine.y, uLine.y + 5, … in
// direction uLine.x, one per invocation, each solved exactly, A_line z_line = t, with its banded
// factor (t the right-hand side mg_relax_right_hand_side.comp left). Lines of one colour lie 5
// apart, outside each other's stencil, so they are solved independently.
//
// Each substitution is a chain of 3 m dependent rows, so its speed is the latency of a row. The
// last kMgBand unknowns ride along in registers (`recent`, the newest first) instead of being read
// back from the store just made, and the next row's band is loaded while this row is computed:
// a row then waits on its arithmetic, not on memory. The sums run in the CPU's order (oldest
// column first); a band slot left of the line's start holds 0 (mg_lines.comp), so the forward
// pass needs no bounds.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = 64) in;

int lineEntry(int l, int direction, int line, int i, int which) {
    ivec2 ij = onLine(direction, line, i / 3);
    return vectorAt(l, ij.y * levelU(l) + ij.x, which) + i % 3;
}

void shiftIn(inout double recent[kMgBand], double newest) {
    for (int c = kMgBand - 1; c > 0; --c) recent[c] = recent[c - 1];
    recent[0] = newest;
}

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, direction = uLine.x;
    int line = uLine.y + 5 * int(gl_GlobalInvocationID.x);
    if (line >= (direction == 0 ? levelV(l) : levelU(l))) return;
    int dofs = 3 * lineLength(l, direction);
    int f = lineAt(l, direction, line);
    double recent[kMgBand];  // z[i − 1 − c] forward, z[i + 1 + c] back
    for (int c = 0; c < kMgBand; ++c) recent[c] = 0.0lf;
    // L y' = t: row i of L is its band, columns i − 8 … i, contiguous.
    double row[kMgBand + 1];
    double right = mgWork[lineEntry(l, direction, line, 0, kMgT)];
    for (int c = 0; c <= kMgBand; ++c) row[c] = mgWork[bandAt(f, 0, c - kMgBand)];
    for (int i = 0; i < dofs; ++i) {
        double next[kMgBand + 1] = row, nextRight = 0.0lf;
        if (i + 1 < dofs) {
            for (int c = 0; c <= kMgBand; ++c) next[c] = mgWork[bandAt(f, i + 1, i + 1 + c - kMgBand)];
            nextRight = mgWork[lineEntry(l, direction, line, i + 1, kMgT)];
        }
        double s = right;
        for (int c = 0; c < kMgBand; ++c) s -= row[c] * recent[kMgBand - 1 - c];
        double y = divide(s, row[kMgBand]);
        mgWork[lineEntry(l, direction, line, i, kMgZ)] = y;
        shiftIn(recent, y);
        row = next;
        right = nextRight;
    }
    // Lᵀ z = y': column i of L, its diagonal and rows i + 1 … i + 8, one entry in each row's band.
    for (int c = 0; c < kMgBand; ++c) recent[c] = 0.0lf;
    double column[kMgBand + 1];
    right = mgWork[lineEntry(l, direction, line, dofs - 1, kMgZ)];
    for (int c = 0; c <= kMgBand; ++c) column[c] = c == 0 ? mgWork[bandAt(f, dofs - 1, dofs - 1)] : 0.0lf;
    for (int i = dofs - 1; i >= 0; --i) {
        double previous[kMgBand + 1] = column, previousRight = 0.0lf;
        if (i > 0) {
            for (int c = 0; c <= kMgBand; ++c)
                previous[c] = i - 1 + c < dofs ? mgWork[bandAt(f, i - 1 + c, i - 1)] : 0.0lf;
            previousRight = mgWork[lineEntry(l, direction, line, i - 1, kMgZ)];
        }
        double s = right;
        for (int c = 1; c <= kMgBand; ++c) s -= column[c] * recent[c - 1];
        double z = divide(s, column[0]);
        mgWork[lineEntry(l, direction, line, i, kMgZ)] = z;
        shiftIn(recent, z);
        column = previous;
        right = previousRight;
    }
    for (int a = 0; a < lineLength(l, direction); ++a) {
        ivec2 ij = onLine(direction, line, a);
        if (pinnedAt(l, ij)) storeVector(l, ij.y * levelU(l) + ij.x, kMgZ, dvec3(0.0lf));
    }
}
