// Adaptive smoothed aggregation (cpu/cpu_aggregation.h): the hierarchy's setup per step, its
// candidates and its V-cycle. P's construction and the Galerkin product are in
// cpu_aggregation_build.cpp.
#include "cpu/cpu_aggregation.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace cloth {

Aggregation::Axis Aggregation::aggregate(int n) {
    Axis axis;
    axis.count = std::max(1, (n + 1) / kAggregate);  // n / 3 rounded: the last one spans 2–4
    axis.of.resize(std::size_t(n));
    for (int i = 0; i < n; ++i) axis.of[std::size_t(i)] = std::min(i / kAggregate, axis.count - 1);
    return axis;
}

// The six rigid motions: translations along x, y, z and rotations about them through each
// aggregate's centroid (the rotations' span with the translations does not depend on the
// centre; the centroid keeps them well conditioned), zero on fixed unknowns.
void Aggregation::rigidCandidates(Level& fine, const std::vector<double>& x) const {
    const BlockGrid& g = fine.a;
    const std::size_t dofs = g.dofs();
    std::vector<double> centre(3 * std::size_t(fine.u.count) * std::size_t(fine.v.count), 0.0);
    std::vector<int> members(centre.size() / 3, 0);
    auto aggregateOf = [&](std::int64_t k) {
        return std::size_t(fine.v.of[std::size_t(k / g.nu)]) * std::size_t(fine.u.count) +
               std::size_t(fine.u.of[std::size_t(k % g.nu)]);
    };
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const std::size_t c = aggregateOf(k);
        for (std::size_t d = 0; d < 3; ++d) centre[3 * c + d] += x[3 * std::size_t(k) + d];
        ++members[c];
    }
    for (std::size_t c = 0; c < members.size(); ++c)
        for (std::size_t d = 0; d < 3; ++d) centre[3 * c + d] /= std::max(1, members[c]);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const std::size_t c = aggregateOf(k), row = 3 * std::size_t(k);
        const double rx = x[row] - centre[3 * c], ry = x[row + 1] - centre[3 * c + 1],
                     rz = x[row + 2] - centre[3 * c + 2];
        const double rotation[3][3] = {{0, -rz, ry}, {rz, 0, -rx}, {-ry, rx, 0}};  // e_d × r
        for (std::size_t d = 0; d < 3; ++d) {
            fine.b[d * dofs + row + d] = 1;
            for (std::size_t e = 0; e < 3; ++e) fine.b[(3 + d) * dofs + row + e] = rotation[d][e];
        }
    }
    for (std::size_t c = 0; c < std::size_t(kRigid); ++c)
        for (std::size_t e = 0; e < dofs; ++e)
            if (g.fixed[e]) fine.b[c * dofs + e] = 0;
}

// The adaptive candidates' start: the last setup's relaxed candidates, orthonormalised, so that
// the relaxation accumulates from step to step as the sheet changes (a subspace iteration of the
// smoother on its slowest modes); a random vector (a fixed seed) for a candidate the others
// nearly span (within 1e-3 of its length) and at the first setup.
void Aggregation::startCandidates(Level& top) {
    const std::size_t n = top.a.dofs(), first = std::size_t(kRigid) * n;
    std::mt19937_64 random(0x5eed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const bool carry = settings_.carryCandidates && carried_.size() == top.b.size() - first;
    std::vector<double> fresh(n), v(n);
    auto orthogonalise = [&](int c) {  // v against candidates [kRigid, c), twice; returns |v|²
        for (int pass = 0; pass < 2; ++pass)
            for (int o = kRigid; o < c; ++o) {
                const double* w = &top.b[std::size_t(o) * n];
                double d = 0;
                for (std::size_t i = 0; i < n; ++i) d += w[i] * v[i];
                for (std::size_t i = 0; i < n; ++i) v[i] -= d * w[i];
            }
        double norm = 0;
        for (std::size_t i = 0; i < n; ++i) norm += v[i] * v[i];
        return norm;
    };
    for (int c = kRigid; c < top.columns; ++c) {
        for (std::size_t i = 0; i < n; ++i) fresh[i] = top.a.fixed[i] ? 0 : uniform(random);
        const double* last = carry ? &carried_[std::size_t(c - kRigid) * n] : fresh.data();
        v.assign(last, last + n);
        double before = 0;
        for (std::size_t i = 0; i < n; ++i) before += v[i] * v[i];
        double norm = orthogonalise(c);
        if (!(norm > 1e-6 * before)) {  // nearly in the others' span: a fresh one
            v = fresh;
            norm = orthogonalise(c);
        }
        double* e = &top.b[std::size_t(c) * n];
        const double scale = norm > 0 ? 1 / std::sqrt(norm) : 0;  // 0: every unknown fixed
        for (std::size_t i = 0; i < n; ++i) e[i] = v[i] * scale;
    }
}

// Candidates [first, columns) relaxed on A e = 0 by `sweeps` symmetric line sweeps: what is
// left is error the sweeps reduce slowly.
void Aggregation::relaxCandidates(Level& level, int first, int sweeps) const {
    const std::size_t dofs = level.a.dofs();
    const std::vector<double> zero(dofs, 0.0);
    for (int c = first; c < level.columns; ++c) {
        double* e = &level.b[std::size_t(c) * dofs];
        for (int s = 0; s < sweeps; ++s) {
            level.smoother.sweep(level.a, zero.data(), e, false);
            level.smoother.sweep(level.a, zero.data(), e, true);
        }
    }
}

void Aggregation::setup(BlockGrid fine, const std::vector<double>& x) {
    levels_.clear();
    levels_.reserve(std::size_t(std::max(1, settings_.maxLevels)));  // coarsen holds references
    levels_.emplace_back();
    Level& top = levels_.back();
    top.a = std::move(fine);
    top.a.imposeFixed();
    top.smoother.factor(top.a);
    top.u = aggregate(top.a.nu);
    top.v = aggregate(top.a.nv);
    top.columns = kRigid + settings_.candidates;
    top.b.assign(std::size_t(top.columns) * top.a.dofs(), 0.0);
    rigidCandidates(top, x);
    startCandidates(top);
    relaxCandidates(top, kRigid, settings_.candidateSweeps);
    carried_.assign(top.b.begin() + std::ptrdiff_t(std::size_t(kRigid) * top.a.dofs()),
                    top.b.end());
    for (int l = 0;; ++l) {
        Level& g = levels_[std::size_t(l)];
        const bool shrinks =
            std::int64_t(aggregate(g.a.nu).count) * aggregate(g.a.nv).count < g.a.count();
        if (l + 1 >= settings_.maxLevels || g.a.dofs() <= settings_.coarsestDofs || !shrinks) break;
        // Each grid's coarse space is built from its own candidates, so they must be near-null
        // on it: the adaptive ones' coarse parts are relaxed again on every grid that is
        // coarsened (on the first coarse grid only, the flat sheet's four-grid cycle took 13
        // iterations where three grids took 4: Aggregation.DeeperGridsKeepTheCyclesStrength).
        if (l > 0) relaxCandidates(g, kRigid, settings_.coarseCandidateSweeps);
        coarsen(l);
    }
    Level& last = levels_.back();
    last.dense.factor(last.a);
    for (Level& g : levels_) {
        g.r.assign(g.a.dofs(), 0.0);
        g.z.assign(g.a.dofs(), 0.0);
        g.t.assign(g.a.dofs(), 0.0);
    }
}

void Aggregation::coarsen(int l) {
    levels_.emplace_back();
    Level& fine = levels_[std::size_t(l)];
    Level& coarse = levels_.back();
    fine.u = aggregate(fine.a.nu);
    fine.v = aggregate(fine.a.nv);
    tentative(fine, coarse);
    if (settings_.smooth) smoothProlongation(fine, coarse.a.b);
    galerkin(fine, coarse);
    coarse.a.imposeFixed();
    coarse.smoother.factor(coarse.a);
}

void Aggregation::prolong(int l, const double* coarse, double* fine) const {
    const Level& g = levels_[std::size_t(l)];
    const BlockGrid& c = levels_[std::size_t(l) + 1].a;
    const std::size_t B = std::size_t(g.a.b), C = std::size_t(c.b);
    for (std::int64_t k = 0; k < g.a.count(); ++k) {
        const int I = g.u.of[std::size_t(k % g.a.nu)], J = g.v.of[std::size_t(k / g.a.nu)];
        for (int s = 0; s < kReach; ++s) {
            const int ci = I + s % 3 - 1, cj = J + s / 3 - 1;
            if (!c.contains(ci, cj)) continue;
            const double* in = coarse + (std::size_t(cj) * std::size_t(c.nu) + std::size_t(ci)) * C;
            const double* blk = &g.p[(std::size_t(k) * kReach + std::size_t(s)) * B * C];
            for (std::size_t r = 0; r < B; ++r) {
                double sum = 0;
                for (std::size_t q = 0; q < C; ++q) sum += blk[r * C + q] * in[q];
                fine[std::size_t(k) * B + r] += sum;
            }
        }
    }
}

void Aggregation::restrict(int l, const double* fine, double* coarse) const {
    const Level& g = levels_[std::size_t(l)];
    const BlockGrid& c = levels_[std::size_t(l) + 1].a;
    const std::size_t B = std::size_t(g.a.b), C = std::size_t(c.b);
    std::fill(coarse, coarse + c.dofs(), 0.0);
    for (std::int64_t k = 0; k < g.a.count(); ++k) {
        const int I = g.u.of[std::size_t(k % g.a.nu)], J = g.v.of[std::size_t(k / g.a.nu)];
        const double* in = fine + std::size_t(k) * B;
        for (int s = 0; s < kReach; ++s) {
            const int ci = I + s % 3 - 1, cj = J + s / 3 - 1;
            if (!c.contains(ci, cj)) continue;
            double* out = coarse + (std::size_t(cj) * std::size_t(c.nu) + std::size_t(ci)) * C;
            const double* blk = &g.p[(std::size_t(k) * kReach + std::size_t(s)) * B * C];
            for (std::size_t r = 0; r < B; ++r)
                for (std::size_t q = 0; q < C; ++q) out[q] += blk[r * C + q] * in[r];
        }
    }
}

void Aggregation::cycle(int l) {
    Level& g = levels_[std::size_t(l)];
    if (l + 1 == levels()) {
        g.dense.solve(g.r.data(), g.z.data());
        return;
    }
    std::fill(g.z.begin(), g.z.end(), 0.0);
    for (int s = 0; s < settings_.sweeps; ++s) g.smoother.sweep(g.a, g.r.data(), g.z.data(), false);
    g.a.residual(g.r.data(), g.z.data(), g.t.data());
    Level& next = levels_[std::size_t(l) + 1];
    restrict(l, g.t.data(), next.r.data());
    cycle(l + 1);
    prolong(l, next.z.data(), g.z.data());
    for (int s = 0; s < settings_.sweeps; ++s) g.smoother.sweep(g.a, g.r.data(), g.z.data(), true);
}

void Aggregation::apply(const double* r, double* z) {
    Level& top = levels_.front();
    std::copy(r, r + top.a.dofs(), top.r.begin());
    cycle(0);
    std::copy(top.z.begin(), top.z.end(), z);
}

}  // namespace cloth
