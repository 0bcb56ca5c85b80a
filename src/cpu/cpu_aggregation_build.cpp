// The aggregation multigrid's coarse grids (cpu/cpu_aggregation.h): the tentative P of each
// aggregate's orthonormalised candidates, its smoothing by block Jacobi and the Galerkin product.
#include <algorithm>
#include <cmath>
#include <random>

#include "cpu/block_kernels.h"
#include "cpu/cpu_aggregation.h"

namespace cloth {

namespace {

// inverse = a⁻¹ for a positive definite n × n a, both in one layout (the transpose's inverse is
// the inverse's transpose), by Gauss–Jordan on a copy.
void invert(std::vector<double> a, double* inverse, std::size_t n) {
    for (std::size_t i = 0; i < n * n; ++i) inverse[i] = i % (n + 1) == 0 ? 1.0 : 0.0;
    for (std::size_t c = 0; c < n; ++c) {
        const double pivot = a[c * n + c];
        for (std::size_t e = 0; e < n; ++e) {
            a[c * n + e] /= pivot;
            inverse[c * n + e] /= pivot;
        }
        for (std::size_t r = 0; r < n; ++r) {
            if (r == c) continue;
            const double f = a[r * n + c];
            if (f == 0) continue;
            for (std::size_t e = 0; e < n; ++e) {
                a[r * n + e] -= f * a[c * n + e];
                inverse[r * n + e] -= f * inverse[c * n + e];
            }
        }
    }
}

// fn(A_km, m, oi, oj) for each neighbour m of vertex k in the stencil of the fine level's grid,
// (oi, oj) m's aggregate less k's (−1…1 each: aggregates span two vertices or more).
template <typename FineLevel, typename Fn>
void forEachNeighbour(const FineLevel& fine, std::int64_t k, const Fn& fn) {
    const BlockGrid& g = fine.a;
    const int i = int(k % g.nu), j = int(k / g.nu);
    const int I = fine.u.of[std::size_t(i)], J = fine.v.of[std::size_t(j)];
    for (int dj = -2; dj <= 2; ++dj)
        for (int di = -2; di <= 2; ++di) {
            if (!g.contains(i + di, j + dj)) continue;
            fn(g.block(k, BlockGrid::slot(di, dj)), std::size_t(k + std::int64_t(dj) * g.nu + di),
               fine.u.of[std::size_t(i + di)] - I, fine.v.of[std::size_t(j + dj)] - J);
        }
}

}  // namespace

// Per aggregate, the candidates' rows on its unknowns (fixed ones left out) orthonormalised by
// modified Gram–Schmidt, twice: P_t's block of the aggregate is Q, the coarse vertex's
// candidates are R. A candidate within 1e-8 of its norm of the span of those before it on the
// aggregate (a corner with fewer unknowns than candidates, a pinned aggregate) gives a coarse
// unknown that is fixed.
void Aggregation::tentative(Level& fine, Level& coarse) const {
    const BlockGrid& g = fine.a;
    const int nc = fine.columns;
    const std::size_t B = std::size_t(g.b), C = std::size_t(nc), dofs = g.dofs();
    coarse.a.resize(fine.u.count, fine.v.count, nc);
    coarse.columns = nc;
    coarse.b.assign(C * coarse.a.dofs(), 0.0);
    fine.p.assign(std::size_t(g.count()) * kReach * B * C, 0.0);
    std::vector<std::vector<std::size_t>> rows(std::size_t(coarse.a.count()));
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const std::size_t agg =
            std::size_t(fine.v.of[std::size_t(k / g.nu)]) * std::size_t(fine.u.count) +
            std::size_t(fine.u.of[std::size_t(k % g.nu)]);
        for (std::size_t r = 0; r < B; ++r)
            if (!g.fixed[std::size_t(k) * B + r]) rows[agg].push_back(std::size_t(k) * B + r);
    }
    const std::size_t coarseDofs = coarse.a.dofs();
    std::vector<double> q;
    for (std::size_t agg = 0; agg < rows.size(); ++agg) {
        const std::vector<std::size_t>& at = rows[agg];
        const std::size_t n = at.size();
        q.assign(n * C, 0.0);  // column c at c n
        for (std::size_t c = 0; c < C; ++c) {
            double* v = &q[c * n];
            for (std::size_t e = 0; e < n; ++e) v[e] = fine.b[c * dofs + at[e]];
            double before = 0;
            for (std::size_t e = 0; e < n; ++e) before += v[e] * v[e];
            double* rCol = &coarse.b[c * coarseDofs + agg * C];  // R's column c
            for (int pass = 0; pass < 2; ++pass)
                for (std::size_t o = 0; o < c; ++o) {
                    const double* w = &q[o * n];
                    double d = 0;
                    for (std::size_t e = 0; e < n; ++e) d += w[e] * v[e];
                    for (std::size_t e = 0; e < n; ++e) v[e] -= d * w[e];
                    rCol[o] += d;
                }
            double after = 0;
            for (std::size_t e = 0; e < n; ++e) after += v[e] * v[e];
            if (after > 0 && after > 1e-16 * before) {
                const double norm = std::sqrt(after);
                for (std::size_t e = 0; e < n; ++e) v[e] /= norm;
                rCol[c] = norm;
            } else {
                std::fill(v, v + n, 0.0);
                coarse.a.fixed[agg * C + c] = 1;
            }
        }
        for (std::size_t e = 0; e < n; ++e) {  // Q's rows into P_t, the aggregate's own block
            const std::size_t k = at[e] / B, r = at[e] % B;
            double* blk = &fine.p[(k * kReach + 4) * B * C];
            for (std::size_t c = 0; c < C; ++c) blk[r * C + c] = q[c * n + e];
        }
    }
}

// P = (I − ω D⁻¹ A) P_t, ω = 4 / (3 ρ(D⁻¹A)) with ρ estimated by 20 power iterations; rows of
// fixed unknowns stay 0.
void Aggregation::smoothProlongation(Level& fine, int coarseB) const {
    const BlockGrid& g = fine.a;
    const std::size_t B = std::size_t(g.b), C = std::size_t(coarseB), BB = B * B;
    std::vector<double> inverse(std::size_t(g.count()) * BB);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const double* d = g.block(k, BlockGrid::slot(0, 0));
        invert(std::vector<double>(d, d + BB), &inverse[std::size_t(k) * BB], B);
    }
    std::vector<double> x(g.dofs()), y(g.dofs());
    std::mt19937_64 random(0x70e5);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    double start = 0;
    for (double& e : x) {
        e = uniform(random);
        start += e * e;
    }
    for (double& e : x) e /= std::sqrt(start);
    double rho = 1;  // |D⁻¹A x| for |x| = 1
    for (int it = 0; it < 20; ++it) {
        g.apply(x.data(), y.data());
        double norm = 0;
        for (std::int64_t k = 0; k < g.count(); ++k) {
            double* out = &x[std::size_t(k) * B];
            std::fill(out, out + B, 0.0);
            blocks::multiplyAdd<0, 1>(&inverse[std::size_t(k) * BB], &y[std::size_t(k) * B], out,
                                      int(B), 1);
            for (std::size_t r = 0; r < B; ++r) norm += out[r] * out[r];
        }
        rho = std::sqrt(norm);
        for (double& e : x) e /= rho;
    }
    const double omega = 4.0 / (3.0 * rho);
    std::vector<double> smoothed(fine.p.size(), 0.0), ap(kReach * B * C);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        std::fill(ap.begin(), ap.end(), 0.0);  // A P_t, by aggregate offset
        forEachNeighbour(fine, k, [&](const double* a, std::size_t m, int oi, int oj) {
            blocks::multiplyAdd<0, 0>(a, &fine.p[(m * kReach + 4) * B * C],
                                      &ap[std::size_t(oi + 1 + 3 * (oj + 1)) * B * C], int(B),
                                      int(C));
        });
        double* out = &smoothed[std::size_t(k) * kReach * B * C];
        std::copy_n(&fine.p[std::size_t(k) * kReach * B * C], kReach * B * C, out);
        for (int s = 0; s < kReach; ++s)
            blocks::multiplyAdd<0, 0>(&inverse[std::size_t(k) * BB], &ap[std::size_t(s) * B * C],
                                      out + std::size_t(s) * B * C, int(B), int(C), -omega);
        for (std::size_t r = 0; r < B; ++r)
            if (g.fixed[std::size_t(k) * B + r])
                for (int s = 0; s < kReach; ++s)
                    std::fill_n(out + std::size_t(s) * B * C + r * C, C, 0.0);
    }
    fine.p.swap(smoothed);
}

// A_c = Pᵀ A P: per fine vertex k, (A P)_k on the 5 × 5 aggregates around k's, then its share
// P_kIᵀ (A P)_kJ of every coarse block (I, J) it reaches.
void Aggregation::galerkin(const Level& fine, Level& coarse) const {
    blocks::dispatch(fine.a.b, [&](auto kB) {
        blocks::dispatch(coarse.a.b, [&](auto kC) {
            galerkinSized<decltype(kB)::value, decltype(kC)::value>(fine, coarse);
        });
    });
}

template <int kB, int kC>
void Aggregation::galerkinSized(const Level& fine, Level& coarse) const {
    const BlockGrid& g = fine.a;
    BlockGrid& c = coarse.a;
    const int b = blocks::size<kB>(g.b), nc = blocks::size<kC>(c.b);
    const std::size_t BC = std::size_t(b) * std::size_t(nc);
    std::vector<double> ap(25 * BC);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const int i = int(k % g.nu), j = int(k / g.nu);
        const int I = fine.u.of[std::size_t(i)], J = fine.v.of[std::size_t(j)];
        std::fill(ap.begin(), ap.end(), 0.0);  // A P, by aggregate offset −2…2
        forEachNeighbour(fine, k, [&](const double* a, std::size_t m, int oi, int oj) {
            for (int s = 0; s < kReach; ++s) {
                const int ti = oi + s % 3 - 1, tj = oj + s / 3 - 1;
                blocks::multiplyAdd<kB, kC>(a, &fine.p[(m * kReach + std::size_t(s)) * BC],
                                            &ap[std::size_t(BlockGrid::slot(ti, tj)) * BC], b, nc);
            }
        });
        for (int s = 0; s < kReach; ++s) {
            const int pi = s % 3 - 1, pj = s / 3 - 1;
            if (!c.contains(I + pi, J + pj)) continue;
            const double* p = &fine.p[(std::size_t(k) * kReach + std::size_t(s)) * BC];
            const std::int64_t row = std::int64_t(J + pj) * c.nu + (I + pi);
            for (int tj = -2; tj <= 2; ++tj)
                for (int ti = -2; ti <= 2; ++ti) {
                    const int di = ti - pi, dj = tj - pj;
                    if (std::abs(di) > 2 || std::abs(dj) > 2 || !c.contains(I + ti, J + tj))
                        continue;
                    blocks::addTransposedProduct<kB, kC>(
                        p, &ap[std::size_t(BlockGrid::slot(ti, tj)) * BC],
                        c.block(row, BlockGrid::slot(di, dj)), b, nc);
                }
        }
    }
}

}  // namespace cloth
