// implicit_euler's multigrid preconditioner on the GPU (PRECONDITIONER_MULTIGRID;
// docs/integrators.md, "Preconditioners"), the V-cycle of src/cpu/cpu_multigrid.h kernel for
// kernel, in double. The hierarchy (src/model/multigrid_levels.h) is fixed by the grid, so the
// host compiles it in: MG_LEVELS holds one ivec4(nu, nv, first, 0) per level, fine first, where
// `first` counts the vertices of the levels above it; MG_TOTAL is the vertices of all levels.
//
// Two storage blocks (bindings the other implicit_euler kernels leave free with this
// preconditioner):
//   mgStencil: every level's system, 25 3×3 blocks per vertex (offsets (−2..2)², slot
//              5(dj + 2) + di + 2), nine doubles each, column by column (a coarse block is not
//              symmetric: P has a rotation term, see prolongationBlocks);
//   mgWork:    the line smoother's banded Cholesky factors (54 doubles per vertex: every row and
//              every column of a grid as one band of half-width 8 unknowns, 9 entries a row),
//              then r, z, t of each vertex (9 doubles), then the coarsest grid's dense factor,
//              then the line solves' chunk transfers (transferAt).

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
// mg_coarsest_factor.comp defines MG_WORK_COHERENT as `coherent`: its invocations read what
// others of its one work group wrote in the same dispatch (GLSL 4.6 §4.10: without it, a
// memoryBarrierBuffer and barrier() need not make those writes visible). The other kernels read
// only what earlier dispatches or they themselves wrote.
#ifndef MG_WORK_COHERENT
#define MG_WORK_COHERENT
#endif
layout(std430, binding = 14) MG_WORK_COHERENT buffer MgWork {
    double mgWork[];
};

// The level the dispatch works on (the coarse one of a Galerkin product, restriction or
// prolongation).
layout(location = 4) uniform int uLevel;
// The smoother's dispatch (mg_relax_right_hand_side.comp, mg_relax.comp) in one value: its level,
// line direction (0 rows, 1 columns) and colour, 16 level + 8 direction + colour. One uniform
// that changes between dispatches, not three: Mesa 22.3's zink (OpenGL over Vulkan, on lavapipe)
// ran these kernels with the direction and the level of an earlier dispatch of the same colour,
// and the V-cycle's z was garbage (docs/gpu.md "Drivers").
layout(location = 5) uniform int uLine;
int lineLevel() { return uLine >> 4; }
int lineDirection() { return (uLine >> 3) & 1; }
int lineColour() { return uLine & 7; }

int levelU(int l) { return kMgLevels[l].x; }
int levelV(int l) { return kMgLevels[l].y; }
int levelFirst(int l) { return kMgLevels[l].z; }

int stencilSlot(int di, int dj) { return 5 * (dj + 2) + di + 2; }
// Whether block (di, dj) of level l can be nonzero: a coarse grid's Galerkin product reaches
// all 25 offsets; the fine grid's springs and bending only the 13 with |di| + |dj| ≤ 2
// (mg_fine.comp leaves the other 12 at 0; src/cpu/cpu_multigrid.h kFinePlaces). The sweeps
// and the first Galerkin product skip those 12 loads.
bool stencilReaches(int l, int di, int dj) { return l > 0 || abs(di) + abs(dj) <= 2; }

// Where block `slot` of vertex k of level l starts in mgStencil.
int blockAt(int l, int k, int slot) { return ((levelFirst(l) + k) * 25 + slot) * 9; }

dmat3 loadBlock(int at) {
    return dmat3(mgStencil[at], mgStencil[at + 1], mgStencil[at + 2], mgStencil[at + 3],
                 mgStencil[at + 4], mgStencil[at + 5], mgStencil[at + 6], mgStencil[at + 7],
                 mgStencil[at + 8]);
}
void storeBlock(int at, dmat3 b) {
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) mgStencil[at + 3 * c + r] = b[c][r];
}
double blockEntry(dmat3 b, int row, int col) { return b[col][row]; }

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

// Where row i (vertex i / 3, coordinate i % 3) of a line's vector `which` lies in mgWork.
int lineEntry(int l, int direction, int line, int i, int which) {
    ivec2 ij = onLine(direction, line, i / 3);
    return vectorAt(l, ij.y * levelU(l) + ij.x, which) + i % 3;
}

int coarsestFirst() { return 63 * MG_TOTAL; }

// The line solves run in chunks of consecutive vertices, one invocation a chunk (mg_relax.comp),
// so that a substitution's chain of dependent rows is a chunk long, not a line. A chunk holds at
// least 4 vertices, so that its last kMgBand rows are its own, and a line at most MG_CHUNKS
// chunks (the invocations of a work group); the last may be shorter.
int chunkVertices(int m) { return max(4, (m + MG_CHUNKS - 1) / MG_CHUNKS); }
int chunkCount(int m) { return (m + chunkVertices(m) - 1) / chunkVertices(m); }
// Per chunk of every line of every relaxed level (src/gpu/gpu_variant.cpp multigridBytes), after
// the coarsest grid's factor, 128 doubles: the forward substitution's transfer (entry 8 t + u:
// how row b − 8 + t of the chunk [a, b) moves with row a − 8 + u before it), then the back
// substitution's (entry 64 + 8 t + u: how row a + t moves with row b + u after it).
int transferAt(int l, int direction, int line, int chunk) {
    int lines = direction == 0 ? line : levelV(l) + line;
    for (int m = 0; m < l; ++m) lines += levelU(m) + levelV(m);
    int coarsest = levelU(MG_LEVEL_COUNT - 1) * levelV(MG_LEVEL_COUNT - 1);
    return coarsestFirst() + 9 * coarsest * coarsest + (lines * MG_CHUNKS + chunk) * 128;
}

// cross(v, y) = crossMatrix(v) y
dmat3 crossMatrix(dvec3 v) { return dmat3(0.0lf, v.z, -v.y, -v.z, 0.0lf, v.x, v.y, -v.x, 0.0lf); }

// The fine index of coarse index I on an axis of n fine vertices: min(2I, n − 1).
int fineOf(int I, int n) { return min(2 * I, n - 1); }

// Whether vertex (i, j) of level l is pinned: a coarse vertex is iff the fine vertex it sits on
// is, down to the cloth's own pins (position.w = 0).
bool pinnedAt(int l, ivec2 ij) {
    for (int m = l; m > 0; --m) ij = ivec2(fineOf(ij.x, levelU(m - 1)), fineOf(ij.y, levelV(m - 1)));
    return positions[ij.y * gridU() + ij.x].w == 0.0;
}

// Row i of P along an axis of n fine vertices (coarse count c): i lies in cell I (between coarse
// I and I + 1) with the weights 1 − w and w (src/cpu/cpu_multigrid.cpp coarsen). A fine index on
// a coarse one belongs to the cell below it (0 to cell 0), so that P keeps radius 2.
void interpolationRow(int i, int n, int c, out int I, out double w) {
    if (c == 1) {
        I = 0;
        w = 0.0lf;
        return;
    }
    I = i == 0 ? 0 : min((i - 1) / 2, c - 2);
    int lo = fineOf(I, n), hi = fineOf(I + 1, n);
    w = divide(double(i - lo), double(hi - lo));
}
// The cells with coarse index I as a corner (I − 1 and I, where they exist), and the fine
// indices [first, last] of cell C.
ivec2 cellsOf(int I, int c) { return ivec2(max(0, I - 1), min(I, max(1, c - 1) - 1)); }
ivec2 cellSpan(int C, int n, int c) {
    if (c == 1) return ivec2(0, n - 1);
    return ivec2(C == 0 ? 0 : fineOf(C, n) + 1, fineOf(C + 1, n));
}

// The position of vertex ij of level l: its fine vertex's (in double).
dvec3 levelPosition(int l, ivec2 ij) {
    for (int m = l; m > 0; --m) ij = ivec2(fineOf(ij.x, levelU(m - 1)), fineOf(ij.y, levelV(m - 1)));
    return dvec3(positions[ij.y * gridU() + ij.x].xyz);
}

// P's blocks of fine vertex ij of level l − 1 (src/cpu/cpu_multigrid.cpp prolongation): one per
// corner c of its cell (c & 1 along u, c >> 1 along v), the bilinear weight times I minus
// [d]× G_c: d is how far the vertex lies off the blend of the corners, G_c the corner's share of
// the cell's least-squares rotation, so that a rigid motion is carried exactly.
void prolongationBlocks(int l, ivec2 ij, out ivec2 cell, out dmat3 p[4]) {
    int f = l - 1, cu = levelU(l), cv = levelV(l);
    double wu, wv;
    interpolationRow(ij.x, levelU(f), cu, cell.x, wu);
    interpolationRow(ij.y, levelV(f), cv, cell.y, wv);
    double w[4] = double[4]((1.0lf - wu) * (1.0lf - wv), wu * (1.0lf - wv), (1.0lf - wu) * wv, wu * wv);
    for (int c = 0; c < 4; ++c) p[c] = dmat3(w[c]);
    if (cu == 1 || cv == 1) return;
    dvec3 X[4], blend = dvec3(0.0lf);
    for (int c = 0; c < 4; ++c) {
        X[c] = levelPosition(l, cell + ivec2(c & 1, c >> 1));
        blend += w[c] * X[c];
    }
    dvec3 d = levelPosition(f, ij) - blend;
    dvec3 a = 0.5lf * ((X[1] - X[0]) + (X[3] - X[2]));
    dvec3 b = 0.5lf * ((X[2] - X[0]) + (X[3] - X[1]));
    double aa = dot(a, a), bb = dot(b, b);
    dmat3 normal = dmat3(aa + bb) - outerProduct(a, a) - outerProduct(b, b);
    double det = determinant(normal);
    if (!(det > 1e-12lf * (aa + bb) * (aa + bb) * (aa + bb))) return;  // a degenerate cell
    // The inverse by the adjugate (glm's order: the transposed cofactors over the determinant).
    double s = divide(1.0lf, det);
    dmat3 m = normal, inverse;
    inverse[0][0] = (m[1][1] * m[2][2] - m[2][1] * m[1][2]) * s;
    inverse[1][0] = -(m[1][0] * m[2][2] - m[2][0] * m[1][2]) * s;
    inverse[2][0] = (m[1][0] * m[2][1] - m[2][0] * m[1][1]) * s;
    inverse[0][1] = -(m[0][1] * m[2][2] - m[2][1] * m[0][2]) * s;
    inverse[1][1] = (m[0][0] * m[2][2] - m[2][0] * m[0][2]) * s;
    inverse[2][1] = -(m[0][0] * m[2][1] - m[2][0] * m[0][1]) * s;
    inverse[0][2] = (m[0][1] * m[1][2] - m[1][1] * m[0][2]) * s;
    inverse[1][2] = -(m[0][0] * m[1][2] - m[1][0] * m[0][2]) * s;
    inverse[2][2] = (m[0][0] * m[1][1] - m[1][0] * m[0][1]) * s;
    dmat3 ca = crossMatrix(a), cb = crossMatrix(b), cd = crossMatrix(d);
    for (int c = 0; c < 4; ++c) {
        double sa = (c & 1) != 0 ? 0.5lf : -0.5lf, sb = (c >> 1) != 0 ? 0.5lf : -0.5lf;
        p[c] -= cd * (inverse * (sa * ca + sb * cb));
    }
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
            if ((skip == 0 && dj == 0) || (skip == 1 && di == 0) || !stencilReaches(l, di, dj))
                continue;
            sum -= loadBlock(blockAt(l, k, stencilSlot(di, dj))) * loadVector(l, k + dj * nu + di, kMgZ);
        }
    return sum;
}

// The dispatch's vertex of level l (a 2-D dispatch of WX × WY groups over the level's grid).
bool levelVertex(int l, out ivec2 ij, out int k) {
    ij = ivec2(gl_GlobalInvocationID.xy);
    k = ij.y * levelU(l) + ij.x;
    return ij.x < levelU(l) && ij.y < levelV(l);
}
