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

// vbd (cpu_rows.h VbdRow) on up to kVbdChunk vertices from k0: each term of the local problems
// in a loop of its own over the chunk's vertices, their sums kept in the chunk's arrays, so each
// loop vectorises across the vertices (their loads five apart); then the Newton steps, and the
// stores after every step is taken.
constexpr int kVbdChunk = 64;

template <typename T>
struct VbdChunk {
    alignas(64) T gx[kVbdChunk], gy[kVbdChunk], gz[kVbdChunk];
    alignas(64) T xx[kVbdChunk], yy[kVbdChunk], zz[kVbdChunk];
    alignas(64) T xy[kVbdChunk], xz[kVbdChunk], yz[kVbdChunk];
    alignas(64) T nx[kVbdChunk], ny[kVbdChunk], nz[kVbdChunk];
    alignas(64) T mass[kVbdChunk];  // m = 1/(1/m), once per vertex
    CLOTH_LANE VbdLane<T> get(int m) const {
        return {gx[m], gy[m], gz[m], xx[m], yy[m], zz[m], xy[m], xz[m], yz[m]};
    }
    CLOTH_LANE void set(int m, const VbdLane<T>& a) {
        gx[m] = a.gx, gy[m] = a.gy, gz[m] = a.gz, xx[m] = a.xx, yy[m] = a.yy, zz[m] = a.zz;
        xy[m] = a.xy, xz[m] = a.xz, yz[m] = a.yz;
    }
};

// The chunk's new positions into the iterate, where the vertex moved (in its own function: the
// steps above read the iterate through restrict pointers).
template <typename T>
void vbdStore(T* __restrict x, T* __restrict y, T* __restrict z, const VbdChunk<T>& c,
              const std::uint8_t* __restrict moved, std::int64_t k0, int n) {
    for (int m = 0; m < n; ++m) {
        if (!moved[m]) continue;
        const std::int64_t k = k0 + 5 * std::int64_t(m);
        x[k] = c.nx[m], y[k] = c.ny[m], z[k] = c.nz[m];
    }
}

// One component of the inertia's gradient, g_m = inertia·(x − y) + drag·(x − x_n) for the
// chunk's vertices m (x, x_n five apart, y fifteen: its three components interleaved).
template <typename T>
void vbdInertiaLoop(T* __restrict g, const T* __restrict x, const T* __restrict y,
                    const T* __restrict start, const T* __restrict mass, T h, T dampingRate,
                    int n) {
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = 5 * std::int64_t(m);
        g[m] = T(0) + vbdInertiaGradient(x[k], y[3 * k], start[k], vbdInertiaWeight(mass[m], h),
                                         vbdDragWeight(mass[m], h, dampingRate));
    }
}

// One component of the bending force subtracted from g, the 13 stencil values through pointers
// of their own (each at the chunk's first vertex, five apart): with offsets the compiler could
// see, it would group the loads and give up on the group of five (hence not inlined either).
template <typename T>
[[gnu::noinline]] void vbdBendingLoop(T* __restrict g, const T* const (&p)[13], T u1, T u0, T v1,
                                      T v0, T plus, T minus, int n) {
    const T* __restrict a0 = p[0], * __restrict a1 = p[1], * __restrict a2 = p[2];
    const T* __restrict a3 = p[3], * __restrict a4 = p[4], * __restrict b0 = p[5];
    const T* __restrict b1 = p[6], * __restrict b2 = p[7], * __restrict c0 = p[8];
    const T* __restrict c1 = p[9], * __restrict c2 = p[10], * __restrict d = p[11];
    const T* __restrict e = p[12];
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = 5 * std::int64_t(m);
        g[m] -= bendingLane(a0[k], a1[k], a2[k], a3[k], a4[k], b0[k], b1[k], b2[k], c0[k], c1[k],
                            c2[k], d[k], e[k], u1, u0, v1, v0, plus, minus);
    }
}

template <typename T>
void vbdChunk(const VbdRow<T>& r, std::int64_t k0, int n, std::uint8_t* __restrict moved) {
    VbdChunk<T> c;
    const T* __restrict px = r.x.x, * __restrict py = r.x.y, * __restrict pz = r.x.z;
    const T* __restrict nx = r.xn.x, * __restrict ny = r.xn.y, * __restrict nz = r.xn.z;
    const T* __restrict inverseMass = r.inverseMass;
    const T h = r.h, dampingRate = r.dampingRate;
    const std::int64_t skip = r.skip;
    for (int m = 0; m < n; ++m) c.mass[m] = T(1) / inverseMass[k0 + 5 * std::int64_t(m)];
    // The inertia first, as addVbdInertia starts the sum from zero.
    vbdInertiaLoop(c.gx, px + k0, r.inertial + 3 * k0, nx + k0, c.mass, h, dampingRate, n);
    vbdInertiaLoop(c.gy, py + k0, r.inertial + 3 * k0 + 1, ny + k0, c.mass, h, dampingRate, n);
    vbdInertiaLoop(c.gz, pz + k0, r.inertial + 3 * k0 + 2, nz + k0, c.mass, h, dampingRate, n);
    for (int m = 0; m < n; ++m) {
        const T mass = c.mass[m];
        const T diagonal = T(0) + (vbdInertiaWeight(mass, h) + vbdDragWeight(mass, h, dampingRate));
        c.xx[m] = diagonal, c.yy[m] = diagonal, c.zz[m] = diagonal;
        c.xy[m] = T(0), c.xz[m] = T(0), c.yz[m] = T(0);
    }
    for (int s = 0; s < r.springs; ++s) {
        const std::int64_t o = r.offset[s];
        const T K = r.stiffness[s], L = r.restLength[s], beta = r.damping[s];
        if (beta > 0) {
            for (int m = 0; m < n; ++m) {
                const std::int64_t k = k0 + 5 * std::int64_t(m), q = k + o;
                VbdLane<T> a = c.get(m);
                vbdSpringLane(px[q] - px[k], py[q] - py[k], pz[q] - pz[k], K, L, a);
                vbdSpringDampingLane(nx[q] - nx[k], ny[q] - ny[k], nz[q] - nz[k],
                                     (px[q] - nx[q]) - (px[k] - nx[k]),
                                     (py[q] - ny[q]) - (py[k] - ny[k]),
                                     (pz[q] - nz[q]) - (pz[k] - nz[k]), beta, L, h, a);
                c.set(m, a);
            }
        } else {
            for (int m = 0; m < n; ++m) {
                const std::int64_t k = k0 + 5 * std::int64_t(m), q = k + o;
                VbdLane<T> a = c.get(m);
                vbdSpringLane(px[q] - px[k], py[q] - py[k], pz[q] - pz[k], K, L, a);
                c.set(m, a);
            }
        }
    }
    if (r.bending) {
        const T u1 = r.wu * T(1), u0 = r.wu * T(-2), v1 = r.wv * T(1), v0 = r.wv * T(-2);
        const T plus = r.t * T(1), minus = r.t * T(-1);
        const std::int64_t nu = r.nu;
        // bendingLane's order: row j's columns −2 … 2, row j − 1's and j + 1's −1 … 1, rows j ∓ 2.
        const std::int64_t at[13] = {-2,      -1,     0,  1,      2,       -nu - 1, -nu,
                                     -nu + 1, nu - 1, nu, nu + 1, -2 * nu, 2 * nu};
        for (int axis = 0; axis < 3; ++axis) {
            const T* base = (axis == 0 ? px : axis == 1 ? py : pz) + k0;
            const T* p[13];
            for (int e = 0; e < 13; ++e) p[e] = base + at[e];
            vbdBendingLoop(axis == 0   ? c.gx
                           : axis == 1 ? c.gy
                                       : c.gz,
                           p, u1, u0, v1, v0, plus, minus, n);
        }
        const T* __restrict w = r.bendDiagonal;
        for (int m = 0; m < n; ++m) {
            const T s = w[k0 + 5 * std::int64_t(m)];
            c.xx[m] += s, c.yy[m] += s, c.zz[m] += s;
        }
    }
    const std::uint8_t* __restrict pinned = r.pinned;
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = k0 + 5 * std::int64_t(m);
        T x = px[k], yk = py[k], z = pz[k];
        const bool stepped = vbdNewtonLane(c.get(m), double(c.mass[m]) / (double(h) * h), x, yk, z);
        c.nx[m] = x, c.ny[m] = yk, c.nz[m] = z;
        const bool free = pinned[k] == 0;  // read in every lane: no masked load
        moved[m] = std::uint8_t(unsigned(stepped) & unsigned(free) & unsigned(k != skip));
    }
    vbdStore(r.x.x, r.x.y, r.x.z, c, moved, k0, n);
}

}  // namespace

template <typename T>
void vbd(const VbdRow<T>& r, int n) {
    for (int m = 0; m < n; m += kVbdChunk)
        vbdChunk(r, r.first + 5 * std::int64_t(m), n - m < kVbdChunk ? n - m : kVbdChunk,
                 r.moved + m);
}

template void vbd(const VbdRow<float>&, int);
template void vbd(const VbdRow<double>&, int);

}  // namespace cloth::CLOTH_ISA_NS
