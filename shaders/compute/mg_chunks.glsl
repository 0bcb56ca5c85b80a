// The line smoother's substitutions over one chunk of a line (multigrid.glsl chunkVertices):
// mg_relax.comp solves a line with them, mg_line_transfers.comp finds how a chunk's ends move
// with the rows around it. Included after multigrid.glsl.
//
// Each substitution is a chain of dependent rows, so its speed is the latency of a row. The last
// kMgBand unknowns ride along in registers (`recent`, the newest first) instead of being read
// back from the store just made, and the next row's band is loaded while this row is computed:
// a row then waits on its arithmetic, not on memory. The sums run in the CPU's order (oldest
// column first, src/cpu/cpu_multigrid.cpp substitutePairs).

void shiftIn(inout double recent[kMgBand], double newest) {
    for (int c = kMgBand - 1; c > 0; --c) recent[c] = recent[c - 1];
    recent[0] = newest;
}

// L y = t over rows [a, b) of the line whose band starts at f: `recent` holds y of rows a − 1,
// a − 2, … a − 8 on entry (a band slot left of the line's start holds 0, mg_lines.comp) and y of
// rows b − 1 … b − 8 on return. The right-hand side is t (kMgT) if `fromT`, else 0; y is stored
// into z (kMgZ) if `store`.
void forwardChunk(int l, int direction, int line, int f, int a, int b, bool fromT, bool store,
                  inout double recent[kMgBand]) {
    double row[kMgBand + 1];  // L's row i: columns i − 8 … i, contiguous
    double right = fromT ? mgWork[lineEntry(l, direction, line, a, kMgT)] : 0.0lf;
    for (int c = 0; c <= kMgBand; ++c) row[c] = mgWork[bandAt(f, a, a + c - kMgBand)];
    for (int i = a; i < b; ++i) {
        double next[kMgBand + 1] = row, nextRight = 0.0lf;
        if (i + 1 < b) {
            for (int c = 0; c <= kMgBand; ++c) next[c] = mgWork[bandAt(f, i + 1, i + 1 + c - kMgBand)];
            if (fromT) nextRight = mgWork[lineEntry(l, direction, line, i + 1, kMgT)];
        }
        double s = right;
        for (int c = 0; c < kMgBand; ++c) s -= row[c] * recent[kMgBand - 1 - c];
        double y = divide(s, row[kMgBand]);
        if (store) mgWork[lineEntry(l, direction, line, i, kMgZ)] = y;
        shiftIn(recent, y);
        row = next;
        right = nextRight;
    }
}

// Lᵀ z = y over rows [a, b) of a line of `dofs` rows, from b − 1 down: `recent` holds z of rows
// b, b + 1, … b + 7 on entry and z of rows a … a + 7 on return. The right-hand side is y, held
// in z (kMgZ), if `fromY`, else 0; z is stored over it if `store`.
void backwardChunk(int l, int direction, int line, int f, int dofs, int a, int b, bool fromY,
                   bool store, inout double recent[kMgBand]) {
    double column[kMgBand + 1];  // L's column i: its diagonal and rows i + 1 … i + 8
    double right = fromY ? mgWork[lineEntry(l, direction, line, b - 1, kMgZ)] : 0.0lf;
    for (int c = 0; c <= kMgBand; ++c)
        column[c] = b - 1 + c < dofs ? mgWork[bandAt(f, b - 1 + c, b - 1)] : 0.0lf;
    for (int i = b - 1; i >= a; --i) {
        double previous[kMgBand + 1] = column, previousRight = 0.0lf;
        if (i > a) {
            for (int c = 0; c <= kMgBand; ++c)
                previous[c] = i - 1 + c < dofs ? mgWork[bandAt(f, i - 1 + c, i - 1)] : 0.0lf;
            if (fromY) previousRight = mgWork[lineEntry(l, direction, line, i - 1, kMgZ)];
        }
        double s = right;
        for (int c = 1; c <= kMgBand; ++c) s -= column[c] * recent[c - 1];
        double z = divide(s, column[0]);
        if (store) mgWork[lineEntry(l, direction, line, i, kMgZ)] = z;
        shiftIn(recent, z);
        column = previous;
        right = previousRight;
    }
}
