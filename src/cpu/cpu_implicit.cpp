// implicit_euler on the CPU (docs/integrators.md): backward Euler linearised once per step,
// solved by a matrix-free conjugate gradient with pins as constraints and dot products that sum
// fixed chunks in order, so the result does not depend on the thread count.
#include <algorithm>
#include <cmath>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"

namespace cloth {

// Σ over all vertices of value(k) (see cpu_solver.h).
template <typename T>
template <typename PerVertex>
double CpuSolver<T>::reduce(Band& band, const Team& team, const PerVertex& value) {
    std::vector<double>& partial = partials_[band.reductions++ & 1];
    for (std::int64_t c = band.begin / chunk_; c * chunk_ < band.end; ++c) {
        double sum = 0;
        for (std::int64_t k = c * chunk_; k < std::min(band.end, (c + 1) * chunk_); ++k)
            sum += value(k);
        partial[std::size_t(c)] = sum;
    }
    // Every thread sums the same chunks in the same order. The other slot lets a fast thread
    // write its next partial sums while a slow one still reads these.
    team.sync();
    double total = 0;
    for (double x : partial) total += x;
    return total;
}

// out = A p = m_k (1 + hc) p + h D p + h² H p on this band (pinned rows 0), H the clamped
// stiffness of the state x_ the step linearises at, D = −∂F/∂v the spring damping's (0 without
// it), plus the grab spring's K I.
template <typename T>
void CpuSolver<T>::systemProduct(const Band& band, const std::vector<Vec3<T>>& p,
                                 std::vector<Vec3<T>>& out) {
    stiffnessProduct(grid_.nu, grid_.nv, springs_, x_, p.data(), pinned_.data(), out.data(),
                     band.begin, band.end, bending_);
    const T h2 = dt_t_ * dt_t_, drag = T(1) + dt_t_ * dampingRate_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        if (pinned_[k]) continue;
        out[k] = (drag / inverseMass_[std::size_t(k)]) * p[k] + h2 * out[k];
        if (features_.springDamping) {  // + h D p, D = −∂F/∂v = Σ βK d̂d̂ᵀ (docs/integrators.md)
            Vec3<T> damped(0);
            addSpringDampingAt(grid_.nu, grid_.nv, springs_, x_, p.data(), k, int(k % grid_.nu),
                               int(k / grid_.nu), damped);
            out[k] -= dt_t_ * damped;
        }
    }
    if (grab_ && grab_->vertex >= band.begin && grab_->vertex < band.end && !pinned_[grab_->vertex])
        out[grab_->vertex] += h2 * grab_->stiffness * p[grab_->vertex];
}

// Backward Euler linearised once (Baraff & Witkin): (m_k (1 + hc) I + h D + h² H) Δv =
// h (F + m_k (g − c v) − h H v), by conjugate gradient with pins as constraints (rows held 0).
template <typename T>
bool CpuSolver<T>::stepImplicit(Band& band, const Team& team, long stepNumber) {
    gatherForces(band);
    const T h = dt_t_;
    // r = b: Hv first (v of the neighbours is the previous step's, already complete).
    stiffnessProduct(grid_.nu, grid_.nv, springs_, x_, v_, pinned_.data(), ap_.data(), band.begin,
                     band.end, bending_);
    if (grab_ && grab_->vertex >= band.begin && grab_->vertex < band.end)
        ap_[grab_->vertex] += grab_->stiffness * v_.get(grab_->vertex);
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const T m = T(1) / inverseMass_[std::size_t(k)];
        const Vec3<T> b =
            pinned_[k] ? Vec3<T>(0)
                       : h * (f_.get(k) + m * (gravity_ - dampingRate_ * v_.get(k)) - h * ap_[k]);
        dv_[k] = Vec3<T>(0);
        r_[k] = b;
        p_[k] = b;
    }
    auto dot = [](const Vec3<T>& a, const Vec3<T>& b) {
        return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
    };
    const double bb = reduce(band, team, [&](std::int64_t k) { return dot(r_[k], r_[k]); });
    const double goal = tolerance_ * tolerance_ * bb;
    double rr = bb;
    int it = 0;
    while (rr > goal && it < maxIterations_) {
        systemProduct(band, p_, ap_);
        const double pap = reduce(band, team, [&](std::int64_t k) { return dot(p_[k], ap_[k]); });
        if (!(pap > 0)) break;  // A is positive definite: only a non-finite state gets here
        const T alpha = T(rr / pap);
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            dv_[k] += alpha * p_[k];
            r_[k] -= alpha * ap_[k];
        }
        const double next = reduce(band, team, [&](std::int64_t k) { return dot(r_[k], r_[k]); });
        const T beta = T(next / rr);
        for (std::int64_t k = band.begin; k < band.end; ++k) p_[k] = r_[k] + beta * p_[k];
        rr = next;
        ++it;
        team.sync();  // the next product reads the neighbours' p
    }
    if (&band == &bands_[0])
        recordSolve(stepNumber, it, bb > 0 ? std::sqrt(rr / bb) : 0.0, rr <= goal);
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> v = v_.get(k) + dv_[k];
        if (!finishStep(band, k, x_.get(k) + h * v, v)) return false;
    }
    return true;
}

template <typename T>
void CpuSolver<T>::recordSolve(long stepNumber, int iterations, double residual, bool converged) {
    SolveStats& s = solveStats_;
    ++s.solves;
    s.iterations += iterations;
    s.mostIterations = std::max(s.mostIterations, iterations);
    if (converged) return;
    if (s.misses++ == 0) s.firstMissStep = stepNumber;
    s.worstResidual = std::max(s.worstResidual, residual);
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here, the rest in cpu_solver.cpp.
#define CLOTH_INSTANTIATE(T)                                                            \
    template bool CpuSolver<T>::stepImplicit(Band&, const Team&, long);                 \
    template void CpuSolver<T>::systemProduct(const Band&, const std::vector<Vec3<T>>&, \
                                              std::vector<Vec3<T>>&);                   \
    template void CpuSolver<T>::recordSolve(long, int, double, bool);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
