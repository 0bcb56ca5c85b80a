// vbd's end of the step on the CPU with row kernels (stepVbd): v = d/h, less the correction of a
// vertex that started inside a collider (model/start_inside.h), then finishStep's pins, colliders
// and check, row by row as the fused Euler sweep ends its rows (cpu_forces.cpp). The colliders run
// through their row code (CpuColliders::applyRow: the same bits as vertex by vertex): on copies of
// the start positions x − d, where a vertex they move started inside, then on the new state.
#include <algorithm>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"
#include "model/start_inside.h"

namespace cloth {

template <typename T>
bool CpuSolver<T>::vbdFinishRows(Band& band) {
    const int nu = grid_.nu;
    const T h = dt_t_;
    const auto collide = [this](Vec3<T>& p, Vec3<T>& w) { colliders_.apply(p, w); };
    const auto surface = [this](const Vec3<T>& p) { return colliders_.surfaceVelocity(p); };
    constexpr int kRun = 64;
    alignas(64) T s[3][kRun], w[3][kRun];
    Vec3<T> start[kRun];  // the run's start positions, before the colliders move s
    auto pin = std::lower_bound(pinList_.begin(), pinList_.end(), band.begin);
    bool ok = true;
    for (int j = band.rowBegin; j < band.rowEnd; ++j) {
        const std::int64_t row = std::int64_t(j) * nu;
        for (int i = 0; i < nu; ++i) v_.set(row + i, phases_.d.get(phases_.at(i, j)) / h);
        for (int c = 0; c < nu && !colliders_.empty(); c += kRun) {
            const int n = std::min(kRun, nu - c);
            for (int m = 0; m < n; ++m) {
                const Vec3<T> p = x_.get(row + c + m) - phases_.d.get(phases_.at(c + m, j));
                start[m] = p;
                s[0][m] = p.x, s[1][m] = p.y, s[2][m] = p.z;
                w[0][m] = w[1][m] = w[2][m] = T(0);
            }
            if (!colliders_.applyRow({s[0], s[1], s[2]}, {w[0], w[1], w[2]}, n, *kernels_))
                continue;
            for (int m = 0; m < n; ++m) {
                const std::int64_t k = row + c + m;
                const Vec3<T>& p = start[m];
                if (pinned_[k] || Vec3<T>(s[0][m], s[1][m], s[2][m]) == p) continue;
                v_.set(k, withoutStartCorrection(p, v_.get(k), h, collide, surface));
            }
        }
        for (; pin != pinList_.end() && *pin < row + nu; ++pin) {  // pins, then colliders (§2)
            x_.set(*pin, pinPosition_[*pin]);
            v_.set(*pin, pinVelocity(*pin));
        }
        if (!colliders_.empty()) colliders_.applyRow(x_.row(row), v_.row(row), nu, *kernels_);
        if (ok && kernels_->anyBad(x_.row(row), v_.row(row), maxSpeed2_, nu))
            ok = reportFirstBad(band, row, row + nu);
    }
    return ok;
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
template bool CpuSolver<float>::vbdFinishRows(Band&);
template bool CpuSolver<double>::vbdFinishRows(Band&);

}  // namespace cloth
