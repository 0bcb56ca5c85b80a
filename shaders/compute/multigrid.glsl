// implicit_euler's multigrid preconditioner on the GPU (PRECONDITIONER_MULTIGRID;
// docs/integrators.md, "Preconditioners"), the V-cycle of src/cpu/cpu_multigrid.h kernel for
// kernel, in double. The hierarchy (src/model/multigrid_levels.h) is fixed by the grid, so the
// host compiles it in: MG_LEVELS holds one ivec4(nu, nv, first, 0) per level, fine first, where
// `first` counts the vertices of the levels above it; MG_TOTAL is the vertices of all levels.
//
// Two storage blocks (bindings the other implicit_euler kernels leave free with this
// preconditioner):
//   mgStencil: every level's system, 25 symmetric 3×3 blocks per vertex (offsets (−2..2)², slot
//              5(dj + 2) + di + 2), six doubles each (xx, xy, xz, yy, yz, zz);
//   mgWork:    the line smoother's banded Cholesky factors (54 doubles per vertex: every row and
//              every column of a grid as one band of half-width 8 unknowns, 9 entries a row),
//              then r, z, t of each vertex (9 doubles), then the coarsest grid's dense factor.

const ivec4 kMgLevels[MG_LEVEL_COUNT] = ivec4[](MG_LEVELS);

// GLSL promises double division and square roots only single precision (GLSL 4.50 §4.7.1), and
// NVIDIA's driver gives no more: at stretch 1e6 N/m the stencil's mass is 1e-8 of its springs,
// under that rounding, and the hierarchy went indefinite. Two Newton steps from the estimate
// (products and fma are exact doubles) restore double precision; an exact estimate stays.
double divide(double a, double b) {
    double y = 1.0lf / b;
    double q = a * y;
    q = fma(fma(-q, b, a), y, q);
    return fma(fma(-q, b, a), y, q);
}
double squareRoot(double x) {
    if (!(x > 0.0lf)) return 0.0lf;
    double y = sqrt(x);
    y = 0.5lf * (y + divide(x, y));
    return 0.5lf * (y + divide(x, y));
}
const int kMgBand = 8;  // a line's half bandwidth in unknowns: 3 × 2 + 2

layout(std430, binding = 4) buffer MgStencil {
    double mgStencil[];
};
layout(std430, binding = 14) buffer MgWork {
    double mgWork[];
};

// The level the dispatch works on (the coarse one of a Galerkin product, restriction or
// prolongation); the smoother's line direction (0 rows, 1 columns) and colour.
layout(location = 4) uniform int uLevel;
layout(location = 5) uniform ivec2 uLine;

int levelU(int l) { return kMgLevels[l].x; }
int levelV(int l) { return kMgLevels[l].y; }
int levelFirst(int l) { return kMgLevels[l].z; }

int stencilSlot(int di, int dj) { return 5 * (dj + 2) + di + 2; }

// Where block `slot` of vertex k of level l starts in mgStencil.
int blockAt(int l, int k, int slot) { return ((levelFirst(l) + k) * 25 + slot) * 6; }

struct Sym3 {
    double xx, xy, xz, yy, yz, zz;
};

Sym3 loadBlock(int at) {
    return Sym3(mgStencil[at], mgStencil[at + 1], mgStencil[at + 2], mgStencil[at + 3],
                mgStencil[at + 4], mgStencil[at + 5]);
}
void storeBlock(int at, Sym3 b) {
    mgStencil[at] = b.xx;
    mgStencil[at + 1] = b.xy;
    mgStencil[at + 2] = b.xz;
    mgStencil[at + 3] = b.yy;
    mgStencil[at + 4] = b.yz;
    mgStencil[at + 5] = b.zz;
}
dvec3 times(Sym3 b, dvec3 w) {
    return dvec3(b.xx * w.x + b.xy * w.y + b.xz * w.z, b.xy * w.x + b.yy * w.y + b.yz * w.z,
                 b.xz * w.x + b.yz * w.y + b.zz * w.z);
}
double blockEntry(Sym3 b, int row, int col) {
    int r = min(row, col), c = max(row, col);
    if (r == 0) return c == 0 ? b.xx : (c == 1 ? b.xy : b.xz);
    if (r == 1) return c == 1 ? b.yy : b.yz;
    return b.zz;
}

// The vectors of level l: r (0), z (1), t (2).
const int kMgR = 0, kMgZ = 1, kMgT = 2;
int vectorAt(int l, int k, int which) { return 54 * MG_TOTAL + 9 * (levelFirst(l) + k) + 3 * which; }
dvec3 loadVector(int l, int k, int which) {
    int at = vectorAt(l, k, which);
    return dvec3(mgWork[at], mgWork[at + 1], mgWork[at + 2]);
}
void storeVector(int l, int k, int which, dvec3 v) {
    int at = vectorAt(l, k, which);
    mgWork[at] = v.x;
    mgWork[at + 1] = v.y;
    mgWork[at + 2] = v.z;
}

// The band of line `line` in `direction` of level l: 3 m rows of 9 entries, L's row i holding
// columns i − 8 … i (the diagonal last).
int lineLength(int l, int direction) { return direction == 0 ? levelU(l) : levelV(l); }
int lineAt(int l, int direction, int line) {
    int nu = levelU(l), nv = levelV(l);
    int base = 54 * levelFirst(l) + (direction == 0 ? 0 : 27 * nu * nv);
    return base + line * 3 * lineLength(l, direction) * (kMgBand + 1);
}
int bandAt(int line, int row, int col) { return line + row * (kMgBand + 1) + (kMgBand - (row - col)); }

// The vertex at position a along line `line` in `direction` of level l.
ivec2 onLine(int direction, int line, int a) { return direction == 0 ? ivec2(a, line) : ivec2(line, a); }

int coarsestFirst() { return 63 * MG_TOTAL; }

// The fine index of coarse index I on an axis of n fine vertices: min(2I, n − 1).
int fineOf(int I, int n) { return min(2 * I, n - 1); }

// Whether vertex (i, j) of level l is pinned: a coarse vertex is iff the fine vertex it sits on
// is, down to the cloth's own pins (position.w = 0).
bool pinnedAt(int l, ivec2 ij) {
    for (int m = l; m > 0; --m) ij = ivec2(fineOf(ij.x, levelU(m - 1)), fineOf(ij.y, levelV(m - 1)));
    return positions[ij.y * gridU() + ij.x].w == 0.0;
}

// Row i of P along an axis of n fine vertices (coarse count c): the coarse indices I and I + 1
// and the weights 1 − w and w of fine index i (src/cpu/cpu_multigrid.cpp coarsen).
void interpolationRow(int i, int n, int c, out int I, out double w) {
    if (c == 1) {
        I = 0;
        w = 0.0lf;
        return;
    }
    I = min(i / 2, c - 2);
    int lo = fineOf(I, n), hi = fineOf(I + 1, n);
    w = divide(double(i - lo), double(hi - lo));
}

// Column I of P along an axis (n fine, c coarse vertices): fine indices [first, last] with
// weight 1 at fineOf(I), falling linearly to 0 at the neighbours' fine indices.
double interpolationWeight(int I, int i, int n, int c) {
    int centre = fineOf(I, n);
    if (i == centre) return 1.0lf;
    if (i < centre) {
        if (I == 0) return 0.0lf;
        int below = fineOf(I - 1, n);
        return i > below ? divide(double(i - below), double(centre - below)) : 0.0lf;
    }
    if (I == c - 1) return 0.0lf;
    int above = fineOf(I + 1, n);
    return i < above ? divide(double(above - i), double(above - centre)) : 0.0lf;
}
// The fine indices column I of P reaches: (fineOf(I − 1), fineOf(I + 1)) exclusive, centre
// included.
ivec2 interpolationSpan(int I, int n, int c) {
    int first = I == 0 ? fineOf(I, n) : fineOf(I - 1, n) + 1;
    int last = I == c - 1 ? fineOf(I, n) : fineOf(I + 1, n) - 1;
    return ivec2(first, last);
}

// r − Σ A_kq z_q at vertex k = (i, j) of level l over its stencil, leaving out the blocks on
// the line through it in direction `skip` (0 its row, 1 its column; −1 none): the residual
// t = r − A z, or a line's right-hand side for the line smoother. 0 on a pinned vertex.
dvec3 residualAt(int l, ivec2 ij, int k, int skip) {
    if (pinnedAt(l, ij)) return dvec3(0.0lf);
    int nu = levelU(l), nv = levelV(l);
    dvec3 sum = loadVector(l, k, kMgR);
    for (int dj = max(-2, -ij.y); dj <= min(2, nv - 1 - ij.y); ++dj)
        for (int di = max(-2, -ij.x); di <= min(2, nu - 1 - ij.x); ++di) {
            if ((skip == 0 && dj == 0) || (skip == 1 && di == 0)) continue;
            sum -= times(loadBlock(blockAt(l, k, stencilSlot(di, dj))),
                         loadVector(l, k + dj * nu + di, kMgZ));
        }
    return sum;
}

// The dispatch's vertex of level l (a 2-D dispatch of WX × WY groups over the level's grid).
bool levelVertex(int l, out ivec2 ij, out int k) {
    ij = ivec2(gl_GlobalInvocationID.xy);
    k = ij.y * levelU(l) + ij.x;
    return ij.x < levelU(l) && ij.y < levelV(l);
}
