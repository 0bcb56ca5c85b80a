// vbd's Chebyshev acceleration on the CPU (docs/integrators.md "vbd"): after a sweep, the
// displacements extrapolated from the two before it, then the colliders' projection.
#include <algorithm>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "model/vbd_colouring.h"

namespace cloth {

// Chebyshev acceleration after sweep n (VBD §3.8) on the displacements: d_n ← ω_n (d̄_n −
// d_{n−2}) + d_{n−2} for the free vertices, the position moved by as much, then the colliders'
// projection again. With the copy in phases, by runs of one phase of a row, so that the
// colliders run on whole runs (vbdCollideRun).
template <typename T>
void CpuSolver<T>::vbdAccelerate(const Band& band, double omega) {
    const T w = T(omega);
    const bool extrapolate = omega > 1;
    // Vertex k's extrapolated iterate (x, d) from its displacement now.
    auto extrapolated = [&](std::int64_t k, const Vec3<T>& now, Vec3<T>& x, Vec3<T>& d) {
        d = w * (now - dBeforeLast_[k]) + dBeforeLast_[k];
        x = x_.get(k) + (d - now);
    };
    auto shift = [&](std::int64_t k, const Vec3<T>& d) {
        dBeforeLast_[k] = dBefore_[k];
        dBefore_[k] = d;
    };
    if (!phases_.active() || !extrapolate) {
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            if (pinned_[k]) continue;
            Vec3<T> x, d = vbdDisplacement(k);
            if (extrapolate) {
                extrapolated(k, Vec3<T>(d), x, d);
                vbdProject(x, d);
                vbdSet(k, x, d);
            }
            shift(k, d);
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
                for (int m = 0; m < n; ++m) {
                    const std::int64_t k = first + std::int64_t(kVbdColours) * m;
                    moved[m] = !pinned_[k];
                    if (!moved[m]) continue;
                    Vec3<T> x, d;
                    extrapolated(k, phases_.d.get(at + m), x, d);
                    x_.set(k, x);
                    phases_.x.set(at + m, x);
                    phases_.d.set(at + m, d);
                }
                if (!colliders_.empty()) vbdCollideRun(first, at, moved, n, nullptr, false);
                for (int m = 0; m < n; ++m)
                    if (moved[m])
                        shift(first + std::int64_t(kVbdColours) * m, phases_.d.get(at + m));
            }
        }
}

template void CpuSolver<float>::vbdAccelerate(const Band&, double);
template void CpuSolver<double>::vbdAccelerate(const Band&, double);

}  // namespace cloth
