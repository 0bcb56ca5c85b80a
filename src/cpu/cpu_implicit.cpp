// implicit_euler on the CPU (docs/integrators.md): backward Euler linearised once per step,
// solved by a matrix-free preconditioned conjugate gradient warm-started from the last step's
// solution, with pins as constraints and dot products that sum fixed chunks in order, so the
// result does not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <limits>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"

namespace cloth {
namespace {

double dot(const auto& a, const auto& b) {
    return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z;
}

}  // namespace

// Σ over all vertices of value(k) (see cpu_solver.h), N sums at once.
template <typename T>
template <int N, typename PerVertex>
std::array<double, N> CpuSolver<T>::reduceN(Band& band, const Team& team, const PerVertex& value) {
    std::vector<double>& partial = partials_[band.reductions++ & 1];
    for (std::int64_t c = band.begin / chunk_; c * chunk_ < band.end; ++c) {
        std::array<double, N> sum{};
        for (std::int64_t k = c * chunk_; k < std::min(band.end, (c + 1) * chunk_); ++k) {
            const std::array<double, N> v = value(k);
            for (int s = 0; s < N; ++s) sum[s] += v[s];
        }
        for (int s = 0; s < N; ++s) partial[std::size_t(N * c + s)] = sum[s];
    }
    // Every thread sums the same chunks in the same order. The other slot lets a fast thread
    // write its next partial sums while a slow one still reads these.
    team.sync();
    std::array<double, N> total{};
    const std::size_t chunks = partial.size() / 2;
    for (std::size_t c = 0; c < chunks; ++c)
        for (int s = 0; s < N; ++s) total[s] += partial[N * c + s];
    return total;
}

template <typename T>
template <typename PerVertex>
double CpuSolver<T>::reduce(Band& band, const Team& team, const PerVertex& value) {
    return reduceN<1>(band, team,
                      [&](std::int64_t k) { return std::array<double, 1>{value(k)}; })[0];
}

template <typename T>
ImplicitSystem<T, Soa3<T>> CpuSolver<T>::system() const {
    ImplicitSystem<T, Soa3<T>> a;
    a.nu = grid_.nu;
    a.nv = grid_.nv;
    a.springs = &springs_;
    a.bending = bending_;
    a.x = &x_;
    a.inverseMass = inverseMass_.data();
    a.pinned = pinned_.data();
    a.h = dt_t_;
    a.drag = T(1) + dt_t_ * dampingRate_;
    a.springDamping = features_.springDamping;
    if (grab_) {
        a.grabVertex = grab_->vertex;
        a.grabStiffness = grab_->stiffness;
    }
    if (!contacts_.empty()) a.contacts = contacts_.data();
    return a;
}

// Backward Euler linearised once (Baraff & Witkin): (m_k (1 + hc) I + h D + h² H) Δv =
// h (F + m_k (g − c v) − h H v), by preconditioned conjugate gradient from the last step's Δv,
// with pins as constraints (rows held 0) and, with colliders, the contacts' normal velocity
// changes as constraints too (model/solve_contact.h: S filters r, A p and z).
template <typename T>
bool CpuSolver<T>::stepImplicit(Band& band, const Team& team, long stepNumber) {
    gatherForces(band);
    const T h = dt_t_;
    const ImplicitSystem<T, Soa3<T>> a = system();
    const bool preconditioned = preconditioner_ != Preconditioner::None;
    const bool jacobi = preconditioner_ == Preconditioner::Jacobi;
    const bool multigrid = preconditioner_ == Preconditioner::Multigrid;
    const bool aggregation = preconditioner_ == Preconditioner::Aggregation;
    const bool contacts = !contacts_.empty();
    auto filtered = [&](std::int64_t k, const Vec3<T>& w) {
        return contacts ? filterContact(contacts_[std::size_t(k)], w) : w;
    };
    const auto collide = [this](Vec3<T>& p, Vec3<T>& w) { colliders_.apply(p, w); };
    const auto surface = [this](const Vec3<T>& p) { return colliders_.surfaceVelocity(p); };
    // r = b: Hv first (v of the neighbours is the previous step's, already complete).
    stiffnessProduct(grid_.nu, grid_.nv, springs_, x_, v_, pinned_.data(), ap_.data(), band.begin,
                     band.end, bending_);
    if (grab_ && grab_->vertex >= band.begin && grab_->vertex < band.end)
        ap_[grab_->vertex] += grab_->stiffness * v_.get(grab_->vertex);
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const T m = T(1) / inverseMass_[std::size_t(k)];
        Vec3<T> b = pinned_[k]
                        ? Vec3<T>(0)
                        : h * (f_.get(k) + m * (gravity_ - dampingRate_ * v_.get(k)) - h * ap_[k]);
        if (pinned_[k]) dv_[k] = Vec3<T>(0);  // a new pin: the last solution moved it
        if (contacts) {
            SolveContact<T>& c = contacts_[std::size_t(k)];
            if (pinned_[k])
                c = {};
            else
                b += m * predictContact(x_.get(k), v_.get(k), gravity_, h, m, collide, surface, c);
            c.load = b;
        }
        r_[k] = b;
        if (jacobi) blockInverse_[k] = pinned_[k] ? Sym3<T>{} : a.diagonal(k).inverse();
    }
    // |b| scales the stopping test (unfiltered: a sheet at rest on a floor has S b ≈ 0). Beside
    // it Σ s_k², s_k the sum of the magnitudes of b_k's terms: a residual within the precision's
    // rounding of them (|r| ≤ ε |s|) is as small as T can tell b from 0, and the solve stops
    // there. A cloth at rest in float otherwise reduced a b of 1e-20 until p·A p underflowed.
    const std::array<double, 2> rhs = reduceN<2>(band, team, [&](std::int64_t k) {
        const double s =
            pinned_[k]
                ? 0.0
                : h * (length(f_.get(k)) +
                       length(gravity_ - dampingRate_ * v_.get(k)) / inverseMass_[std::size_t(k)] +
                       h * length(ap_[k])) +
                      length(r_[k]);
        return std::array<double, 2>{dot(r_[k], r_[k]), s * s};
    });
    double bb = rhs[0];
    const double roundoff = std::numeric_limits<T>::epsilon() / 2;
    const double floor = roundoff * roundoff * rhs[1];
    // The warm start: r = b − A Δv₀ with Δv₀ the last step's solution. Where it is no better a
    // guess than 0 (|r| ≥ |b|: a state just written, a jolt), the solve starts from 0.
    a.apply(dv_.data(), ap_.data(), band.begin, band.end);
    const double warm = reduce(band, team, [&](std::int64_t k) {
        const Vec3<T> r = filtered(k, r_[k]) - ap_[k];
        return dot(r, r);
    });
    const bool fromZero = !(warm < bb);
    if (contacts) {
        // Δv₀ = S Δv (or 0) + the fixed part on every contact, then r = S (b − A Δv₀).
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            const SolveContact<T>& c = contacts_[std::size_t(k)];
            dv_[k] = filterContact(c, fromZero ? Vec3<T>(0) : dv_[k]) + fixedChange(c);
        }
        team.sync();  // the product reads the neighbours' Δv₀
        a.apply(dv_.data(), ap_.data(), band.begin, band.end);
        for (std::int64_t k = band.begin; k < band.end; ++k)
            r_[k] = filtered(k, filtered(k, r_[k]) - ap_[k]);
        // A new contact's z n can leave a first residual far above |b| (a vertex stopped from
        // 1 m/s): the test is then relative to that residual, which float can reduce 10⁻⁶ times.
        bb = std::max(bb, reduce(band, team, [&](std::int64_t k) { return dot(r_[k], r_[k]); }));
    } else {
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            if (fromZero)
                dv_[k] = Vec3<T>(0);
            else
                r_[k] -= ap_[k];
        }
    }
    // The multigrid hierarchy's stencils at this state (every thread; it ends with a sync).
    if (multigrid || aggregation) multigrid_.linearise(a, cycleThreads(band, team));
    if (aggregation) {  // its setup on the first thread, from the fine stencil just assembled
        if (&band == &bands_[0]) setupAggregation();
        team.sync();
    }
    const double goal = std::max(tolerance_ * tolerance_ * bb, floor);
    // z = M⁻¹ r: the block-Jacobi step is local, so it fuses with the sums r·r and r·z; the
    // V-cycle needs the whole r (after the sum r·r, which tells whether it is needed at all).
    const std::vector<Vec3<T>>& z = preconditioned ? z_ : r_;
    auto residualSums = [&](std::int64_t k) {
        if (jacobi) z_[k] = filtered(k, blockInverse_[k] * r_[k]);
        return std::array<double, 2>{dot(r_[k], r_[k]), dot(r_[k], z[k])};
    };
    auto residual = [&]() -> std::array<double, 2> {
        if (!multigrid && !aggregation) return reduceN<2>(band, team, residualSums);
        const double squared =
            reduce(band, team, [&](std::int64_t k) { return dot(r_[k], r_[k]); });
        if (squared <= goal) return {squared, 0};
        if (aggregation)
            applyAggregation(band, team);  // ends with a sync
        else
            multigrid_.apply(r_, z_, cycleThreads(band, team));  // ends with a sync
        if (contacts)
            for (std::int64_t k = band.begin; k < band.end; ++k) z_[k] = filtered(k, z_[k]);
        return {squared, reduce(band, team, [&](std::int64_t k) { return dot(r_[k], z_[k]); })};
    };
    std::array<double, 2> sums = residual();
    double rr = sums[0], rz = sums[1];
    for (std::int64_t k = band.begin; k < band.end; ++k) p_[k] = z[k];
    team.sync();  // the product reads the neighbours' p
    int it = 0;
    while (rr > goal && it < maxIterations_) {
        a.apply(p_.data(), ap_.data(), band.begin, band.end);
        const double pap = reduce(band, team, [&](std::int64_t k) { return dot(p_[k], ap_[k]); });
        if (!(pap > 0)) break;  // A is positive definite: only a non-finite state gets here
        const T alpha = T(rz / pap);
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            dv_[k] += alpha * p_[k];
            r_[k] = filtered(k, r_[k] - alpha * ap_[k]);
        }
        ++it;
        sums = residual();
        rr = sums[0];
        if (rr <= goal) break;
        const T beta = T(sums[1] / rz);
        // r and p are filtered again after each sum: rounding leaves a filtered vector a normal
        // part of ε times its operands, which no S A p can reduce (r) or which β p carries on
        // and grows until p·A p turns negative (p).
        for (std::int64_t k = band.begin; k < band.end; ++k)
            p_[k] = filtered(k, z[k] + beta * p_[k]);
        rz = sums[1];
        team.sync();  // the next product reads the neighbours' p
    }
    if (&band == &bands_[0])
        solveStats_.record(stepNumber, it, bb > 0 ? std::sqrt(rr / bb) : 0.0, rr <= goal,
                           !(rr <= goal) && it < maxIterations_);
    if (contacts) {
        // Each contact's impulse J = (A Δv)_k − b_k sets its grip for the next step; A Δv
        // unfiltered, over the neighbours' final Δv.
        team.sync();
        ImplicitSystem<T, Soa3<T>> unfiltered = a;
        unfiltered.contacts = nullptr;
        unfiltered.apply(dv_.data(), ap_.data(), band.begin, band.end);
        for (std::int64_t k = band.begin; k < band.end; ++k) {
            SolveContact<T>& c = contacts_[std::size_t(k)];
            c.grip = nextGrip(c, x_.get(k), v_.get(k), gravity_, h,
                              T(1) / inverseMass_[std::size_t(k)], ap_[k], collide);
        }
        team.sync();  // the finish below writes x, which the other bands' products read
    }
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> v = v_.get(k) + dv_[k], x = x_.get(k) + h * v;
        const Vec3<T> left = contacts ? contactVelocity(contacts_[std::size_t(k)], x_.get(k),
                                                        v_.get(k), gravity_, h, v, surface)
                                      : v;
        if (!finishStep(band, k, x, left)) return false;
    }
    return true;
}

// The aggregation multigrid's hierarchy at this step: its fine grid is the geometric multigrid's
// fine stencil (linearised just before, in double), its candidates' rigid motions those of the
// vertices' positions. One thread builds it (the others wait): its setup is not shared yet.
template <typename T>
void CpuSolver<T>::setupAggregation() {
    BlockGrid fine;
    multigrid_.fineGrid(fine);
    aggregationX_.resize(3 * std::size_t(grid_.count()));
    for (std::int64_t k = 0; k < grid_.count(); ++k)
        for (int d = 0; d < 3; ++d)
            aggregationX_[3 * std::size_t(k) + std::size_t(d)] = double(x_.get(k)[d]);
    aggregation_.setup(std::move(fine), aggregationX_);
    aggregationR_.resize(aggregationX_.size());
    aggregationZ_.resize(aggregationX_.size());
}

// z = V r by the aggregation's V-cycle, in double, on the first thread; every thread calls it
// and it ends with a sync.
template <typename T>
void CpuSolver<T>::applyAggregation(const Band& band, const Team& team) {
    team.sync();  // every band's r is complete
    if (&band == &bands_[0]) {
        for (std::int64_t k = 0; k < grid_.count(); ++k)
            for (int d = 0; d < 3; ++d)
                aggregationR_[3 * std::size_t(k) + std::size_t(d)] = r_[k][d];
        aggregation_.apply(aggregationR_.data(), aggregationZ_.data());
        for (std::int64_t k = 0; k < grid_.count(); ++k)
            for (int d = 0; d < 3; ++d)
                z_[k][d] = T(aggregationZ_[3 * std::size_t(k) + std::size_t(d)]);
    }
    team.sync();
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here, the rest in cpu_solver.cpp.
#define CLOTH_INSTANTIATE(T)                                            \
    template bool CpuSolver<T>::stepImplicit(Band&, const Team&, long); \
    template ImplicitSystem<T, Soa3<T>> CpuSolver<T>::system() const;   \
    template void CpuSolver<T>::setupAggregation();                     \
    template void CpuSolver<T>::applyAggregation(const Band&, const Team&);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
