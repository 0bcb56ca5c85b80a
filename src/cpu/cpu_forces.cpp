// The CPU force pass (DESIGN.md §2) and the explicit/symplectic Euler sweep built on it.
//
// Row by row over structure-of-arrays positions: each "upward" spring's coefficient
// c = K (|d| − L)/|d| is computed once per spring into a ring of the last three rows, and each
// vertex then gathers its 12 neighbours in the table's order as f += c d, reading a downward
// spring's coefficient where its far end computed it, in this row or one of the two below (c is
// the same for d and −d, so every vertex gets the bits the vertex-by-vertex path gives it).
// Borders need no separate path: each spring's loop runs over the columns where that spring
// exists. The scalar path (gatherForcesScalar) is the first CPU backend's, kept as the oracle.
#include <algorithm>
#include <cmath>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"
#include "model/bending.h"
#include "model/forces.h"

namespace cloth {

// The coefficients of row j's upward springs into ring slot j % 3; with gatherLater, those of
// the springs to the rows above only at the two border columns on each side: forceRow's gather
// computes the others. With spring damping, every column's damping coefficient too, into the
// damping ring: like the spring's, computed once for both ends of the spring.
template <typename T>
void CpuSolver<T>::coefficientRow(Band& band, int j, bool gatherLater) {
    const int nu = grid_.nu, nv = grid_.nv;
    T* ring = band.coefficients.data() + std::size_t(j % 3) * upwardSprings_ * nu;
    const std::int64_t k = std::int64_t(j) * nu;
    for (const RowSpring& s : rowSprings_) {
        if (!s.upward || j + s.dj >= nv) continue;
        const int i0 = std::max(0, -s.di), i1 = std::min(nu, nu - s.di);
        auto run = [&](int a, int b, T stiffness) {
            if (b <= a) return;
            kernels_->coefficients(x_.row(k + a), x_.row(k + s.dj * nu + a + s.di), stiffness,
                                   s.restLength, ring + std::size_t(s.slot) * nu + a, b - a);
        };
        // A material's structural spring on a border line has half the stiffness
        // (model/grid.h onBorderLine): along u the whole first and last row, along v the first
        // and last column. 0.5·K times the rest is the bits of 0.5 times K times the rest.
        // (The spring's damping βK likewise.)
        auto byBorder = [&](int a, int b, T full, const auto& each) {
            const T half = T(0.5) * full;
            if (b <= a) return;
            if (!s.halvedOnBorder) return each(a, b, full);
            if (s.dj == 0) return each(a, b, j == 0 || j == nv - 1 ? half : full);
            if (a == 0) each(0, 1, half);
            if (b == nu) each(std::max(a, nu - 1), nu, half);
            if (std::max(a, 1) < std::min(b, nu - 1))
                each(std::max(a, 1), std::min(b, nu - 1), full);
        };
        auto columns = [&](int a, int b) { byBorder(a, b, s.stiffness, run); };
        if (gatherLater && kComputedInGather[s.table]) {
            columns(i0, 2);
            columns(nu - 2, i1);
        } else {
            columns(i0, i1);
        }
        if (features_.springDamping) {
            byBorder(i0, i1, s.damping, [&](int a, int b, T damping) {
                T* out = band.dampingCoefficients.data() +
                         (std::size_t(j % 3) * upwardSprings_ + s.slot) * nu + a;
                const std::int64_t q = k + s.dj * nu + a + s.di;
                kernels_->dampingCoefficients(x_.row(k + a), x_.row(q), v_.row(k + a), v_.row(q),
                                              damping, s.restLength, out, b - a);
            });
        }
    }
}

// The coefficient of spring s for the vertex at column i of row j: an upward spring's is at its
// own vertex, a downward one's at its far end (row j + dj, column i + di).
template <typename T>
const T* CpuSolver<T>::coefficientAt(const Band& band, const RowSpring& s, int j, int i,
                                     bool damping) const {
    const int nu = grid_.nu;
    const int cj = s.upward ? j : j + s.dj, ci = s.upward ? i : i + s.di;
    const T* ring = damping ? band.dampingCoefficients.data() : band.coefficients.data();
    return ring + (std::size_t(cj % 3) * upwardSprings_ + s.slot) * nu + ci;
}

// Row j's forces into f: the springs in table order, then the wind, then the grab. Columns two
// or more from the border of rows two or more from the border gather all their springs in one
// loop; the rest take each spring's loop over the columns where it exists.
template <typename T>
void CpuSolver<T>::forceRow(Band& band, int j, Row3<T> f) {
    const int nu = grid_.nu, nv = grid_.nv;
    const std::int64_t k = std::int64_t(j) * nu;
    const bool interior = interiorRow(j);
    const int inner0 = interior ? 2 : nu, inner1 = interior ? nu - 2 : nu;
    auto springByspring = [&](int a, int b) {  // columns [a, b)
        std::fill(f.x + a, f.x + b, T(0));
        std::fill(f.y + a, f.y + b, T(0));
        std::fill(f.z + a, f.z + b, T(0));
        for (const RowSpring& s : rowSprings_) {
            const int qj = j + s.dj;
            const int i0 = std::max(a, -s.di), i1 = std::min(b, nu - s.di);
            if (qj < 0 || qj >= nv || i1 <= i0) continue;
            kernels_->accumulate(f + i0, x_.row(k + i0), x_.row(std::int64_t(qj) * nu + i0 + s.di),
                                 coefficientAt(band, s, j, i0), i1 - i0);
        }
    };
    springByspring(0, inner0);
    if (interior) {
        GatherRow<T> g;
        g.p = x_.row(k + 2);
        for (const RowSpring& s : rowSprings_) {
            g.q[s.table] = x_.row(std::int64_t(j + s.dj) * nu + 2 + s.di);
            g.c[s.table] = coefficientAt(band, s, j, 2);
            g.out[s.table] = const_cast<T*>(g.c[s.table]);  // the band's own ring
            g.stiffness[s.table] = s.stiffness;
            g.restLength[s.table] = s.restLength;
        }
        kernels_->gather[families_](f + 2, g, nu - 4);
        springByspring(inner1, nu);
    }
    if (bending_.active()) {  // after the springs, as in the vertex-by-vertex path
        auto at = [&](int qi, int qj) { return x_.get(std::int64_t(qj) * nu + qi); };
        auto scalar = [&](int a, int b) {
            for (int i = a; i < b; ++i) {
                const Vec3<T> force = bendingForce<T>(bending_, i, j, at);
                f.x[i] += force.x;
                f.y[i] += force.y;
                f.z[i] += force.z;
            }
        };
        // Rows and columns two or more from the border have every stencil of bendingForce: one
        // vectorised loop; the rest vertex by vertex.
        if (j >= 2 && j < nv - 2 && nu > 4) {
            BendingRow<T> g;
            for (int r = 0; r < 5; ++r) g.rows[r] = x_.row(std::int64_t(j - 2 + r) * nu + 2);
            g.wu = T(bending_.alongU * BendingWeights::share(j, nv));
            g.wv = T(bending_.alongV * BendingWeights::share(2, nu));
            g.t = T(bending_.twist);
            scalar(0, 2);
            kernels_->bending(f + 2, g, nu - 4);
            scalar(nu - 2, nu);
        } else {
            scalar(0, nu);
        }
    }
    if (features_.springDamping) {  // after the bending, spring by spring as the scalar path
        for (const RowSpring& s : rowSprings_) {
            const int qj = j + s.dj, i0 = std::max(0, -s.di), i1 = std::min(nu, nu - s.di);
            if (qj < 0 || qj >= nv || i1 <= i0) continue;
            kernels_->accumulate(f + i0, x_.row(k + i0), x_.row(std::int64_t(qj) * nu + i0 + s.di),
                                 coefficientAt(band, s, j, i0, true), i1 - i0);
        }
    }
    if (features_.wind) {  // central differences, clamped at the border (DESIGN.md §2)
        const ConstRow3<T> row = x_.row(k), down = x_.row(std::int64_t(std::max(j - 1, 0)) * nu),
                           up = x_.row(std::int64_t(std::min(j + 1, nv - 1)) * nu);
        const Vec3<T> w = windDirection_;
        auto columns = [&](int i, int n) {
            kernels_->wind(f + i, row + std::max(i - 1, 0), row + std::min(i + 1, nu - 1), down + i,
                           up + i, w.x, w.y, w.z, windStrengthAt(i, j), n);
        };
        columns(0, 1);
        if (nu > 2) columns(1, nu - 2);
        if (nu > 1) columns(nu - 1, 1);
    }
    // The user's grab spring, F = K (target − x), part of F like any spring.
    if (grab_ && grab_->vertex >= k && grab_->vertex < k + nu) {
        const std::int64_t i = grab_->vertex - k;
        const Vec3<T> g = grabForce(x_.get(grab_->vertex), grab_->target, grab_->stiffness);
        f.x[i] += g.x;
        f.y[i] += g.y;
        f.z[i] += g.z;
    }
}

template <typename T>
template <typename RowDone>
void CpuSolver<T>::sweepRows(Band& band, const RowDone& rowDone) {
    for (int j = std::max(0, band.rowBegin - 2); j < band.rowEnd; ++j) {
        const bool mine = j >= band.rowBegin;  // rows before are the band above's: no gather
        coefficientRow(band, j, mine && interiorRow(j));
        if (mine) rowDone(j);  // rows j − 2 … j of coefficients are in the ring
    }
}

template <typename T>
void CpuSolver<T>::gatherForces(Band& band) {
    if (!kernels_) return gatherForcesScalar(band.begin, band.end);
    sweepRows(band, [&](int j) { forceRow(band, j, f_.row(std::int64_t(j) * grid_.nu)); });
}

// One sweep does the whole step: row j's forces, from the old positions x_, are used at once to
// update row j into xNext_ and v_ (no force array goes to memory and back), then pins, colliders
// and the instability check on that row. Neighbouring bands only read x_, so one barrier per
// step suffices, and the sweep always completes the step, even past an unstable vertex. With
// spring damping the gather reads the neighbours' velocities too, so the new ones go to vNext_
// (the row copied, then updated in place), which swaps with v_ at the end of the step.
template <typename T>
bool CpuSolver<T>::stepEulerFused(Band& band, bool symplectic) {
    const int nu = grid_.nu;
    const auto update = symplectic ? kernels_->symplecticEuler : kernels_->explicitEuler;
    const Row3<T> f = band.force.row(0);
    auto pin = std::lower_bound(pinList_.begin(), pinList_.end(), band.begin);
    Soa3<T>& vOut = features_.springDamping ? vNext_ : v_;
    bool ok = true;
    sweepRows(band, [&](int j) {
        const std::int64_t k = std::int64_t(j) * nu;
        forceRow(band, j, f);
        const Row3<T> v = vOut.row(k);
        if (&vOut != &v_) {
            const ConstRow3<T> old = v_.row(k);
            std::copy_n(old.x, nu, v.x);
            std::copy_n(old.y, nu, v.y);
            std::copy_n(old.z, nu, v.z);
        }
        update({x_.row(k), f, v, xNext_.row(k), inverseMass_.data() + k, dt_t_, dampingRate_,
                gravity_.x, gravity_.y, gravity_.z},
               nu);
        for (; pin != pinList_.end() && *pin < k + nu; ++pin) {  // pins, then colliders (§2)
            xNext_.set(*pin, pinPosition_[*pin]);
            vOut.set(*pin, pinVelocity(*pin));
        }
        if (!colliders_.empty()) colliders_.applyRow(xNext_.row(k), v, nu, *kernels_);
        if (ok && kernels_->anyBad(xNext_.row(k), v, maxSpeed2_, nu))
            ok = reportFirstBad(band, k, k + nu);
    });
    return ok;
}

// The first vertex of [begin, end) that fails the instability test (finishStep's), reported.
template <typename T>
bool CpuSolver<T>::reportFirstBad(Band& band, std::int64_t begin, std::int64_t end) {
    const Soa3<T>& x = fused() ? xNext_ : x_;
    const Soa3<T>& vel = fused() && features_.springDamping ? vNext_ : v_;
    for (std::int64_t k = begin; k < end; ++k) {
        const Vec3<T> p = x.get(k), v = vel.get(k);
        if (!badVertex(p.x, p.y, p.z, v.x, v.y, v.z, maxSpeed2_)) continue;
        reportBad(band, k, p, glm::dot(v, v));
        return false;
    }
    return true;
}

// The first CPU backend's force pass, vertex by vertex: the oracle of the row kernels. Vertices
// two or more away from every border skip the bounds checks.
template <typename T>
void CpuSolver<T>::gatherForcesScalar(std::int64_t begin, std::int64_t end) {
    const int nu = grid_.nu, nv = grid_.nv;
    auto at = [&](int i, int j) { return x_.get(std::int64_t(j) * nu + i); };
    int i = int(begin % nu), j = int(begin / nu);
    for (std::int64_t k = begin; k < end; ++k) {
        Vec3<T> f(0);
        const Vec3<T> p = x_.get(k);
        const bool interior = i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2;
        for (const Spring& s : springs_) {
            const int qi = i + s.di, qj = j + s.dj;
            if (!interior && (qi < 0 || qi >= nu || qj < 0 || qj >= nv)) continue;
            f += springForce(p, x_.get(k + s.indexOffset), stiffnessAt(s, i, j, nu, nv),
                             s.restLength);
        }
        if (bending_.active()) f += bendingForce<T>(bending_, i, j, at);
        if (features_.springDamping) addSpringDampingAt(nu, nv, springs_, x_, v_, k, i, j, f);
        if (features_.wind) {
            const Vec3<T> n = vertexNormal<T>(nu, nv, i, j, at), w = windDirection_;
            addWind(n.x, n.y, n.z, w.x, w.y, w.z, windStrengthAt(i, j), f.x, f.y, f.z);
        }
        f_.set(k, f);
        if (++i == nu) {
            i = 0;
            ++j;
        }
    }
    if (grab_ && grab_->vertex >= begin && grab_->vertex < end)
        f_.set(grab_->vertex, f_.get(grab_->vertex) + grabForce(x_.get(grab_->vertex),
                                                                grab_->target, grab_->stiffness));
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                                                     \
    template void CpuSolver<T>::coefficientRow(Band&, int, bool);                                \
    template const T* CpuSolver<T>::coefficientAt(const Band&, const RowSpring&, int, int, bool) \
        const;                                                                                   \
    template void CpuSolver<T>::forceRow(Band&, int, Row3<T>);                                   \
    template void CpuSolver<T>::gatherForces(Band&);                                             \
    template void CpuSolver<T>::gatherForcesScalar(std::int64_t, std::int64_t);                  \
    template bool CpuSolver<T>::stepEulerFused(Band&, bool);                                     \
    template bool CpuSolver<T>::reportFirstBad(Band&, std::int64_t, std::int64_t);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
