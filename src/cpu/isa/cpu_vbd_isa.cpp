// The vbd row kernel of cpu/cpu_rows.h (RowKernels::vbd) for one instruction set: compiled with
// cpu_rows_isa.cpp, with the same namespace and flags (see there). Each term of a run's local
// problems goes through model/vbd_lane.h, the functions the vertex-by-vertex path
// (model/vbd_local.h) calls: the same bits.
#include <cstdint>

#include "cpu/cpu_rows.h"
#include "model/bending.h"
#include "model/vbd_lane.h"

#ifndef CLOTH_ISA_NS
#error "CLOTH_ISA_NS names the instruction set this file is compiled for"
#endif

namespace cloth::CLOTH_ISA_NS {
namespace {

#ifndef CLOTH_ISA_VECTOR_BYTES
#error "CLOTH_ISA_VECTOR_BYTES gives the instruction set's widest vector"
#endif

// vbd (cpu_rows.h VbdRow) on up to kVbdChunk vertices from m0: each term of the local problems
// in a loop of its own over the chunk's vertices, their sums kept in the chunk's arrays, so each
// loop vectorises across the vertices (every load contiguous: the arrays are in phases); then
// the Newton steps, and the stores after every step is taken. The loops that compute run over
// whole vectors (vbdLanes): a run's last vector would otherwise go through the compiler's scalar
// epilogue, which cost as much as the vectors before it (docs/performance.md). The lanes past
// the run read what lies beyond it in phases (VbdPhases' slack at the end) and are never stored;
// where another thread may be writing there, the caller asks for the run's length alone
// (VbdRow::wholeVectors).
constexpr int kVbdChunk = 64;

template <typename T>
constexpr int vbdLanes(int n) {
    constexpr int width = CLOTH_ISA_VECTOR_BYTES / int(sizeof(T));
    static_assert(kVbdChunk % width == 0 && width - 1 <= kVbdSlack, "whole vectors fit");
    return (n + width - 1) / width * width;
}

template <typename T>
struct VbdChunk {
    alignas(64) T gx[kVbdChunk], gy[kVbdChunk], gz[kVbdChunk];
    alignas(64) T xx[kVbdChunk], yy[kVbdChunk], zz[kVbdChunk];
    alignas(64) T xy[kVbdChunk], xz[kVbdChunk], yz[kVbdChunk];
    alignas(64) T nx[kVbdChunk], ny[kVbdChunk], nz[kVbdChunk];  // the new positions
    alignas(64) T dx[kVbdChunk], dy[kVbdChunk], dz[kVbdChunk];  // the new displacements
    alignas(64) T mass[kVbdChunk];                              // m = 1/(1/m), once per vertex
    CLOTH_LANE VbdLane<T> get(int m) const {
        return {gx[m], gy[m], gz[m], xx[m], yy[m], zz[m], xy[m], xz[m], yz[m]};
    }
    CLOTH_LANE void set(int m, const VbdLane<T>& a) {
        gx[m] = a.gx, gy[m] = a.gy, gz[m] = a.gz, xx[m] = a.xx, yy[m] = a.yy, zz[m] = a.zz;
        xy[m] = a.xy, xz[m] = a.xz, yz[m] = a.yz;
    }
};

// The chunk's new positions, where the vertex moved, into the iterate in phases (contiguous,
// from a) and in the grid's order (five apart, from k); in its own function: the steps above read
// the iterate through restrict pointers.
template <typename T>
void vbdStore(Row3<T> phases, Row3<T> grid, const VbdChunk<T>& c,
              const std::uint8_t* __restrict moved, std::int64_t a, std::int64_t k, int n) {
    T* __restrict px = phases.x + a, * __restrict py = phases.y + a, * __restrict pz = phases.z + a;
    for (int m = 0; m < n; ++m) {
        if (!moved[m]) continue;
        px[m] = c.nx[m], py[m] = c.ny[m], pz[m] = c.nz[m];
    }
    T* __restrict gx = grid.x + k, * __restrict gy = grid.y + k, * __restrict gz = grid.z + k;
    for (int m = 0; m < n; ++m) {
        if (!moved[m]) continue;
        const std::int64_t q = 5 * std::int64_t(m);
        gx[q] = c.nx[m], gy[q] = c.ny[m], gz[q] = c.nz[m];
    }
}

// The chunk's new displacements, where the vertex moved, into phases (the only copy the sweeps
// keep).
template <typename T>
void vbdStoreDisplacements(Row3<T> phases, const VbdChunk<T>& c,
                           const std::uint8_t* __restrict moved, std::int64_t a, int n) {
    T* __restrict px = phases.x + a, * __restrict py = phases.y + a, * __restrict pz = phases.z + a;
    for (int m = 0; m < n; ++m) {
        if (!moved[m]) continue;
        px[m] = c.dx[m], py[m] = c.dy[m], pz[m] = c.dz[m];
    }
}

// One component of the inertia's gradient, g_m = inertia·(d − ŷ) + drag·d for the chunk's
// vertices m.
template <typename T>
void vbdInertiaLoop(T* __restrict g, const T* __restrict d, const T* __restrict y,
                    const T* __restrict mass, T h, T dampingRate, int n) {
    for (int m = 0; m < n; ++m)
        g[m] = T(0) + vbdInertiaGradient(d[m], y[m], vbdInertiaWeight(mass[m], h),
                                         vbdDragWeight(mass[m], h, dampingRate));
}

// One component of the bending force subtracted from g, the 13 stencil values through pointers
// of their own (each at the chunk's first vertex).
template <typename T>
void vbdBendingLoop(T* __restrict g, const T* const (&p)[13], T u1, T u0, T v1, T v0, T plus,
                    T minus, int n) {
    const T* __restrict a0 = p[0], * __restrict a1 = p[1], * __restrict a2 = p[2];
    const T* __restrict a3 = p[3], * __restrict a4 = p[4], * __restrict b0 = p[5];
    const T* __restrict b1 = p[6], * __restrict b2 = p[7], * __restrict c0 = p[8];
    const T* __restrict c1 = p[9], * __restrict c2 = p[10], * __restrict d = p[11];
    const T* __restrict e = p[12];
    for (int m = 0; m < n; ++m)
        g[m] -= bendingLane(a0[m], a1[m], a2[m], a3[m], a4[m], b0[m], b1[m], b2[m], c0[m], c1[m],
                            c2[m], d[m], e[m], u1, u0, v1, v0, plus, minus);
}

// A chunk's sums started with the inertia, as addVbdInertia starts them from zero: the masses
// m = 1/(1/m), the gradient's inertia and drag on the displacements d against ŷ, and the
// Hessian's diagonal.
template <typename T>
void vbdInertiaChunk(VbdChunk<T>& c, const T* __restrict inverseMass, ConstRow3<T> d,
                     ConstRow3<T> y, T h, T dampingRate, int lanes) {
    for (int m = 0; m < lanes; ++m) c.mass[m] = T(1) / inverseMass[m];
    vbdInertiaLoop(c.gx, d.x, y.x, c.mass, h, dampingRate, lanes);
    vbdInertiaLoop(c.gy, d.y, y.y, c.mass, h, dampingRate, lanes);
    vbdInertiaLoop(c.gz, d.z, y.z, c.mass, h, dampingRate, lanes);
    for (int m = 0; m < lanes; ++m) {
        const T mass = c.mass[m];
        const T diagonal = T(0) + (vbdInertiaWeight(mass, h) + vbdDragWeight(mass, h, dampingRate));
        c.xx[m] = diagonal, c.yy[m] = diagonal, c.zz[m] = diagonal;
        c.xy[m] = T(0), c.xz[m] = T(0), c.yz[m] = T(0);
    }
}

template <typename T>
void vbdChunk(const VbdRow<T>& r, int m0, int n) {
    VbdChunk<T> c;
    const int lanes = r.wholeVectors ? vbdLanes<T>(n) : n;
    const std::int64_t a0 = r.at + m0;
    const T* __restrict px = r.px.x + a0, * __restrict py = r.px.y + a0, * __restrict pz = r.px.z + a0;
    const T* __restrict dx = r.pd.x + a0, * __restrict dy = r.pd.y + a0, * __restrict dz = r.pd.z + a0;
    const T h = r.h, dampingRate = r.dampingRate, inverseH = T(1) / r.h;
    vbdInertiaChunk(c, r.inverseMass + a0, {dx, dy, dz}, r.py + a0, h, dampingRate, lanes);
    for (int s = 0; s < r.springs; ++s) {
        const std::int64_t o = r.offset[s];
        const T* __restrict qx = px + o, * __restrict qy = py + o, * __restrict qz = pz + o;
        const T K = r.stiffness[s], L = r.restLength[s], beta = r.damping[s];
        if (beta > 0) {
            const T* __restrict qdx = dx + o, * __restrict qdy = dy + o, * __restrict qdz = dz + o;
            for (int m = 0; m < lanes; ++m) {
                VbdLane<T> a = c.get(m);
                const T ex = qx[m] - px[m], ey = qy[m] - py[m], ez = qz[m] - pz[m];
                const T wx = qdx[m] - dx[m], wy = qdy[m] - dy[m], wz = qdz[m] - dz[m];
                vbdSpringLane(ex, ey, ez, K, L, a);
                vbdSpringDampingLane(ex - wx, ey - wy, ez - wz, wx, wy, wz, beta, L, inverseH, a);
                c.set(m, a);
            }
        } else {
            for (int m = 0; m < lanes; ++m) {
                VbdLane<T> a = c.get(m);
                vbdSpringLane(qx[m] - px[m], qy[m] - py[m], qz[m] - pz[m], K, L, a);
                c.set(m, a);
            }
        }
    }
    if (r.bending) {
        const T u1 = r.wu * T(1), u0 = r.wu * T(-2), v1 = r.wv * T(1), v0 = r.wv * T(-2);
        const T plus = r.t * T(1), minus = r.t * T(-1);
        for (int axis = 0; axis < 3; ++axis) {
            const T* base = axis == 0 ? px : axis == 1 ? py : pz;
            const T* p[13];
            for (int e = 0; e < 13; ++e) p[e] = base + r.bendAt[e];
            vbdBendingLoop(axis == 0   ? c.gx
                           : axis == 1 ? c.gy
                                       : c.gz,
                           p, u1, u0, v1, v0, plus, minus, lanes);
        }
        const T* __restrict w = r.bendDiagonal + a0;
        for (int m = 0; m < lanes; ++m) {
            const T s = w[m];
            c.xx[m] += s, c.yy[m] += s, c.zz[m] += s;
        }
    }
    if (r.contactWeight) {  // the friction after every other term, as vbdVertex adds it
        const T* __restrict ux = r.contactSlide.x + a0, * __restrict uy = r.contactSlide.y + a0;
        const T* __restrict uz = r.contactSlide.z + a0, * __restrict w = r.contactWeight + a0;
        const T* __restrict cx = r.contactNormal.x + a0, * __restrict cy = r.contactNormal.y + a0;
        const T* __restrict cz = r.contactNormal.z + a0;
        for (int m = 0; m < lanes; ++m) {
            VbdLane<T> a = c.get(m);
            vbdFrictionLane(dx[m] - ux[m], dy[m] - uy[m], dz[m] - uz[m], cx[m], cy[m], cz[m], w[m],
                            r.epsilon, a);
            c.set(m, a);
        }
        T* const* out = r.hessian;
        for (int m = 0; m < lanes; ++m) {
            out[0][m0 + m] = c.xx[m], out[1][m0 + m] = c.yy[m], out[2][m0 + m] = c.zz[m];
            out[3][m0 + m] = c.xy[m], out[4][m0 + m] = c.xz[m], out[5][m0 + m] = c.yz[m];
        }
    }
    const std::uint8_t* __restrict pinned = r.pinned + a0;
    std::uint8_t* __restrict moved = r.moved + m0;
    const std::int64_t k0 = r.first + 5 * std::int64_t(m0);
    for (int m = 0; m < lanes; ++m) {
        T sx, sy, sz;
        const bool stepped =
            vbdNewtonLane(c.get(m), double(c.mass[m]) / (double(h) * h), sx, sy, sz);
        c.nx[m] = px[m] + sx, c.ny[m] = py[m] + sy, c.nz[m] = pz[m] + sz;
        c.dx[m] = dx[m] + sx, c.dy[m] = dy[m] + sy, c.dz[m] = dz[m] + sz;
        const bool free = pinned[m] == 0;  // read in every lane: no masked load
        const bool grabbed = k0 + 5 * std::int64_t(m) == r.skip;
        moved[m] = std::uint8_t(unsigned(stepped) & unsigned(free) & unsigned(!grabbed));
    }
    vbdStore(r.px, r.x, c, moved, a0, k0, n);
    vbdStoreDisplacements(r.pd, c, moved, a0, n);
}

}  // namespace

// cpu_rows.h VbdBatch: the terms as vbdChunk adds them (vbdVertex's order), from the gathered
// lanes; an absent spring's lane keeps its sums (a choice, not a branch).
template <typename T>
void vbdBatch(VbdBatch<T>& b, int n) {
    VbdChunk<T> c;
    const int lanes = vbdLanes<T>(n);
    const T h = b.h, dampingRate = b.dampingRate, inverseH = T(1) / b.h;
    const T* __restrict px = b.p[0], * __restrict py = b.p[1], * __restrict pz = b.p[2];
    const T* __restrict dx = b.d[0], * __restrict dy = b.d[1], * __restrict dz = b.d[2];
    vbdInertiaChunk(c, b.inverseMass, {dx, dy, dz}, {b.y[0], b.y[1], b.y[2]}, h, dampingRate,
                    lanes);
    for (int s = 0; s < b.springs; ++s) {
        const T* __restrict qx = b.q[s][0], * __restrict qy = b.q[s][1], * __restrict qz = b.q[s][2];
        const T* __restrict qdx = b.qd[s][0], * __restrict qdy = b.qd[s][1];
        const T* __restrict qdz = b.qd[s][2];
        const T* __restrict K = b.stiffness[s], * __restrict beta = b.damping[s];
        const std::uint8_t* __restrict present = b.present[s];
        const T L = b.restLength[s];
        const bool damped = b.damped[s];
        for (int m = 0; m < lanes; ++m) {
            const VbdLane<T> a = c.get(m);
            VbdLane<T> t = a;
            const T ex = qx[m] - px[m], ey = qy[m] - py[m], ez = qz[m] - pz[m];
            vbdSpringLane(ex, ey, ez, K[m], L, t);
            if (damped) {
                const T wx = qdx[m] - dx[m], wy = qdy[m] - dy[m], wz = qdz[m] - dz[m];
                vbdSpringDampingLane(ex - wx, ey - wy, ez - wz, wx, wy, wz, beta[m], L, inverseH,
                                     t);
            }
            c.set(m, present[m] ? t : a);
        }
    }
    if (b.bending)
        for (int m = 0; m < lanes; ++m) {
            c.gx[m] -= b.bend[0][m], c.gy[m] -= b.bend[1][m], c.gz[m] -= b.bend[2][m];
            const T s = b.bendDiagonal[m];
            c.xx[m] += s, c.yy[m] += s, c.zz[m] += s;
        }
    if (b.friction)
        for (int m = 0; m < lanes; ++m) {
            VbdLane<T> a = c.get(m);
            vbdFrictionLane(dx[m] - b.slide[0][m], dy[m] - b.slide[1][m], dz[m] - b.slide[2][m],
                            b.normal[0][m], b.normal[1][m], b.normal[2][m], b.weight[m], b.epsilon,
                            a);
            c.set(m, a);
        }
    for (int m = 0; m < lanes; ++m) {
        const VbdLane<T> a = c.get(m);
        T sx, sy, sz;
        b.stepped[m] = vbdNewtonLane(a, double(c.mass[m]) / (double(h) * h), sx, sy, sz);
        b.step[0][m] = sx, b.step[1][m] = sy, b.step[2][m] = sz;
        b.lane[0][m] = a.gx, b.lane[1][m] = a.gy, b.lane[2][m] = a.gz;
        b.lane[3][m] = a.xx, b.lane[4][m] = a.yy, b.lane[5][m] = a.zz;
        b.lane[6][m] = a.xy, b.lane[7][m] = a.xz, b.lane[8][m] = a.yz;
    }
}

template void vbdBatch(VbdBatch<float>&, int);
template void vbdBatch(VbdBatch<double>&, int);

template <typename T>
void vbd(const VbdRow<T>& r, int n) {
    for (int m = 0; m < n; m += kVbdChunk) vbdChunk(r, m, n - m < kVbdChunk ? n - m : kVbdChunk);
}

template void vbd(const VbdRow<float>&, int);
template void vbd(const VbdRow<double>&, int);

}  // namespace cloth::CLOTH_ISA_NS
