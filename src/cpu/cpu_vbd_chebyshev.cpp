// vbd's Chebyshev acceleration on the CPU (docs/integrators.md "vbd"): after a sweep, the
// displacements extrapolated from the two before it, then the colliders' projection.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "cpu/cpu_solver.h"
#include "model/vbd_colouring.h"

namespace cloth {

namespace {

template <typename R>
auto component(R r, int c) {
    return c == 0 ? r.x : c == 1 ? r.y : r.z;
}

// One component of a run's Chebyshev step where moved[m]: d ← ω (d − d_{n−2}) + d_{n−2} and x
// moved by as much (the vertex-by-vertex path's operations). A run without pins (`allMoved`)
// takes no choice, so that its loop vectorises.
template <bool allMoved, typename T>
void extrapolateRun(Row3<T> x, Row3<T> d, ConstRow3<T> last, const std::uint8_t* moved, T w, int c,
                    int n) {
    T* __restrict xc = component(x, c);
    T* __restrict dc = component(d, c);
    const T* __restrict lc = component(last, c);
    const std::uint8_t* __restrict free = moved;
    for (int m = 0; m < n; ++m) {
        const T now = dc[m], next = w * (now - lc[m]) + lc[m];
        if (allMoved || free[m]) xc[m] = xc[m] + (next - now), dc[m] = next;
    }
}

// d_{n−2} ← d_{n−1}, d_{n−1} ← d for one component of a run, where moved[m].
template <bool allMoved, typename T>
void shiftRun(Row3<T> last, Row3<T> before, ConstRow3<T> d, const std::uint8_t* moved, int c,
              int n) {
    T* __restrict lc = component(last, c);
    T* __restrict bc = component(before, c);
    const T* __restrict dc = component(d, c);
    const std::uint8_t* __restrict free = moved;
    for (int m = 0; m < n; ++m) {
        if (allMoved || free[m]) lc[m] = bc[m], bc[m] = dc[m];
    }
}

// The run's moved positions into the grid's order (five apart).
template <typename T>
void storeGridRun(Row3<T> grid, ConstRow3<T> phases, const std::uint8_t* moved, int n) {
    T* __restrict gx = grid.x, * __restrict gy = grid.y, * __restrict gz = grid.z;
    const T* __restrict px = phases.x, * __restrict py = phases.y, * __restrict pz = phases.z;
    const std::uint8_t* __restrict free = moved;
    for (int m = 0; m < n; ++m) {
        if (!free[m]) continue;
        const std::int64_t q = std::int64_t(kVbdColours) * m;
        gx[q] = px[m], gy[q] = py[m], gz[q] = pz[m];
    }
}

}  // namespace

// Chebyshev acceleration after sweep n (VBD §3.8) on the displacements: d_n ← ω_n (d̄_n −
// d_{n−2}) + d_{n−2} for the free vertices, the position moved by as much, then the colliders'
// projection again. With the copy in phases, by runs of one phase of a row, so that the
// colliders run on whole runs (vbdCollideRun).
template <typename T>
void CpuSolver<T>::vbdAccelerate(const Band& band, double omega) {
    const T w = T(omega);
    const bool extrapolate = omega > 1;
    if (!phases_.active() || !extrapolate) {
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            if (pinned_[k]) continue;
            const std::int64_t c = vbdContactAt(k);  // where the iterates before are kept
            Vec3<T> d = vbdDisplacement(k);
            if (extrapolate) {
                const Vec3<T> now = d, last = dBeforeLast_.get(c);
                d = w * (now - last) + last;
                Vec3<T> x = x_.get(k) + (d - now);
                vbdProject(x, d);
                vbdSet(k, x, d);
            }
            dBeforeLast_.set(c, dBefore_.get(c));
            dBefore_.set(c, d);
        }
        return;
    }
    const int nu = grid_.nu;
    constexpr int kRun = 64;
    std::uint8_t moved[kRun];
    for (int j = band.rowBegin; j < band.rowEnd; ++j)
        for (int p = 0; p < kVbdColours && p < nu; ++p) {
            const int count = (nu - p + kVbdColours - 1) / kVbdColours;
            for (int m0 = 0; m0 < count; m0 += kRun) {
                const int n = std::min(kRun, count - m0);
                const std::int64_t first =
                    std::int64_t(j) * nu + p + std::int64_t(kVbdColours) * m0;
                const std::int64_t at = phases_.at(p, j) + m0;
                const std::uint8_t* pinned = phases_.pinned.data() + at;
                unsigned all = 1;
                for (int m = 0; m < n; ++m) {
                    moved[m] = pinned[m] == 0;
                    all &= moved[m];
                }
                const auto step = all ? &extrapolateRun<true, T> : &extrapolateRun<false, T>;
                const auto shift = all ? &shiftRun<true, T> : &shiftRun<false, T>;
                // The iterate's copy in phases holds x_'s bits: x + (d − now) from either.
                for (int c = 0; c < 3; ++c)
                    step(phases_.x.row(at), phases_.d.row(at), std::as_const(dBeforeLast_).row(at),
                         moved, w, c, n);
                storeGridRun(x_.row(first), std::as_const(phases_.x).row(at), moved, n);
                if (!colliders_.empty()) vbdCollideRun(first, at, moved, n, nullptr, false);
                for (int c = 0; c < 3; ++c)
                    shift(dBeforeLast_.row(at), dBefore_.row(at), std::as_const(phases_.d).row(at),
                          moved, c, n);
            }
        }
}

template void CpuSolver<float>::vbdAccelerate(const Band&, double);
template void CpuSolver<double>::vbdAccelerate(const Band&, double);

}  // namespace cloth
