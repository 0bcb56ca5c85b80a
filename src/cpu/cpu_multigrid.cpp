// The multigrid V-cycle of cpu/cpu_multigrid.h.
#include "cpu/cpu_multigrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cloth {
namespace {

// Σ_i w_i f(i) over the fine indices i that coarse index I of `axis` gathers (P's column I):
// weight 1 at at[I], falling linearly to 0 at its neighbours at[I ∓ 1].
template <typename Axis, typename Fn>
void forEachFine(const Axis& axis, int I, const Fn& fn) {
    const int n = int(axis.at.size()), centre = axis.at[std::size_t(I)];
    fn(centre, 1.0);
    if (I > 0) {
        const int below = axis.at[std::size_t(I - 1)];
        for (int i = below + 1; i < centre; ++i) fn(i, double(i - below) / (centre - below));
    }
    if (I < n - 1) {
        const int above = axis.at[std::size_t(I + 1)];
        for (int i = centre + 1; i < above; ++i) fn(i, double(above - i) / (above - centre));
    }
}

// The coarse indices fine index i interpolates from, with their weights (P's row i), nonzero.
template <typename Axis, typename Fn>
void forEachCoarse(const Axis& axis, int i, const Fn& fn) {
    const int I = axis.lower[std::size_t(i)];
    const double w = double(axis.weight[std::size_t(i)]);
    if (w < 1) fn(I, 1 - w);
    if (w > 0) fn(I + 1, w);
}

constexpr int stencilSlot(int di, int dj) {
    return 5 * (dj + 2) + di + 2;
}

}  // namespace

template <typename T>
typename CpuMultigrid<T>::Axis CpuMultigrid<T>::coarsen(int n) {
    Axis a;
    const int coarse = coarsenedCount(n);
    for (int I = 0; I < coarse; ++I) a.at.push_back(std::min(2 * I, n - 1));
    for (int i = 0; i < n; ++i) {
        int I = 0;
        while (I + 2 < coarse && a.at[std::size_t(I + 1)] <= i) ++I;
        if (coarse == 1) {
            a.lower.push_back(0);
            a.weight.push_back(T(0));
            continue;
        }
        const int lo = a.at[std::size_t(I)], hi = a.at[std::size_t(I + 1)];
        a.lower.push_back(I);
        a.weight.push_back(T(double(i - lo) / (hi - lo)));
    }
    return a;
}

template <typename T>
void CpuMultigrid<T>::configure(int nu, int nv) {
    levels_.clear();
    configured_ = true;
    for (const MultigridLevel& size : multigridLevels(nu, nv)) {
        Level level;
        level.nu = size.nu;
        level.nv = size.nv;
        if (!levels_.empty()) {
            level.u = coarsen(levels_.back().nu);
            level.v = coarsen(levels_.back().nv);
        }
        levels_.push_back(std::move(level));
    }
    for (std::size_t l = 0; l < levels_.size(); ++l) {
        Level& level = levels_[l];
        const std::size_t n = std::size_t(level.count());
        level.a.assign(n * kStencil, Sym3<S>{});
        level.lines[0].assign(std::size_t(level.nv) * 3 * std::size_t(level.nu) * (kBand + 1), 0.0);
        level.lines[1].assign(std::size_t(level.nu) * 3 * std::size_t(level.nv) * (kBand + 1), 0.0);
        level.pinned.assign(n, 0);
        level.t.assign(n, Vec3<S>(0));
        level.r.assign(n, Vec3<S>(0));
        level.z.assign(n, Vec3<S>(0));
    }
    const std::size_t dofs = 3 * std::size_t(levels_.back().count());
    cholesky_.assign(dofs * dofs, 0.0);
    solve_.assign(dofs, 0.0);
}

template <typename T>
std::pair<std::int64_t, std::int64_t> CpuMultigrid<T>::slice(int nu, int nv,
                                                             const CycleThreads& threads) {
    const int rowBegin = int(std::int64_t(nv) * threads.index / threads.count);
    const int rowEnd = int(std::int64_t(nv) * (threads.index + 1) / threads.count);
    return {std::int64_t(rowBegin) * nu, std::int64_t(rowEnd) * nu};
}

// The fine stencil read off the matrix-free product: p = e_d on every unpinned vertex of colour
// (i mod 5, j mod 5) gives (A p)_k = column d of A_kq for the one vertex q of that colour within
// k's 5×5 window. 75 products on this thread's rows, with its own probe vectors.
template <typename T>
void CpuMultigrid<T>::probeFine(const ProbeSystem& fine, const CycleThreads& threads) {
    Level& level = levels_[0];
    const int nu = level.nu, nv = level.nv;
    const std::int64_t n = level.count();
    std::vector<Vec3<S>>& p = probe_[std::size_t(threads.index)];
    std::vector<Vec3<S>>& out = probed_[std::size_t(threads.index)];
    if (std::int64_t(p.size()) != n) {
        p.assign(std::size_t(n), Vec3<S>(0));
        out.assign(std::size_t(n), Vec3<S>(0));
    }
    const auto [begin, end] = slice(nu, nv, threads);
    const int rowBegin = int(begin / nu), rowEnd = int(end / nu);
    const int probeBegin = std::max(0, rowBegin - 2), probeEnd = std::min(nv, rowEnd + 2);
    for (std::int64_t k = begin; k < end; ++k) {
        level.pinned[std::size_t(k)] = fine.pinned[k];
        for (int o = 0; o < kStencil; ++o) level.a[std::size_t(k * kStencil + o)] = Sym3<S>{};
    }
    for (int cj = 0; cj < 5; ++cj)
        for (int ci = 0; ci < 5; ++ci)
            for (int d = 0; d < 3; ++d) {
                for (int j = probeBegin + ((cj - probeBegin) % 5 + 5) % 5; j < probeEnd; j += 5)
                    for (int i = ci; i < nu; i += 5) {
                        const std::int64_t q = std::int64_t(j) * nu + i;
                        if (!fine.pinned[q]) p[std::size_t(q)][d] = S(1);
                    }
                if (begin < end) fine.apply(p.data(), out.data(), begin, end);
                for (std::int64_t k = begin; k < end; ++k) {
                    if (fine.pinned[k]) continue;
                    const int i = int(k % nu), j = int(k / nu);
                    int di = ((ci - i) % 5 + 5) % 5, dj = ((cj - j) % 5 + 5) % 5;
                    if (di > 2) di -= 5;
                    if (dj > 2) dj -= 5;
                    if (i + di < 0 || i + di >= nu || j + dj < 0 || j + dj >= nv) continue;
                    if (fine.pinned[k + std::int64_t(dj) * nu + di]) continue;
                    Sym3<S>& b = level.a[std::size_t(k * kStencil + stencilSlot(di, dj))];
                    const Vec3<S> c(out[std::size_t(k)]);
                    if (d == 0) b.xx = c.x, b.xy = c.y, b.xz = c.z;
                    if (d == 1) b.yy = c.y, b.yz = c.z;
                    if (d == 2) b.zz = c.z;
                }
                for (int j = probeBegin + ((cj - probeBegin) % 5 + 5) % 5; j < probeEnd; j += 5)
                    for (int i = ci; i < nu; i += 5)
                        p[std::size_t(std::int64_t(j) * nu + i)][d] = S(0);
            }
    for (std::int64_t k = begin; k < end; ++k)
        if (fine.pinned[k])
            level.a[std::size_t(k * kStencil + stencilSlot(0, 0))] = Sym3<S>::identity(1);
}

// Level l's stencil A_l = Pᵀ A_{l−1} P on this thread's coarse rows: for every fine vertex k that
// coarse vertex K gathers (weight w_K) and every block A_kq, the coarse vertices Q that q
// interpolates from (weight w_Q) get w_K w_Q A_kq. Pinned vertices on either grid take no part.
template <typename T>
void CpuMultigrid<T>::galerkin(int l, const CycleThreads& threads) {
    const Level& f = levels_[std::size_t(l - 1)];
    Level& c = levels_[std::size_t(l)];
    const auto [begin, end] = slice(c.nu, c.nv, threads);
    for (std::int64_t K = begin; K < end; ++K) {
        const int I = int(K % c.nu), J = int(K / c.nu);
        const std::int64_t centre =
            std::int64_t(c.v.at[std::size_t(J)]) * f.nu + c.u.at[std::size_t(I)];
        c.pinned[std::size_t(K)] = f.pinned[std::size_t(centre)];
    }
    threads.sync();  // the pins of the neighbours' rows
    for (std::int64_t K = begin; K < end; ++K) {
        Sym3<S>* row = &c.a[std::size_t(K * kStencil)];
        for (int o = 0; o < kStencil; ++o) row[o] = Sym3<S>{};
        if (c.pinned[std::size_t(K)]) {
            row[stencilSlot(0, 0)] = Sym3<S>::identity(1);
            continue;
        }
        const int I = int(K % c.nu), J = int(K / c.nu);
        forEachFine(c.v, J, [&](int j, double wj) {
            forEachFine(c.u, I, [&](int i, double wi) {
                const std::int64_t k = std::int64_t(j) * f.nu + i;
                if (f.pinned[std::size_t(k)]) return;
                const Sym3<S>* blocks = &f.a[std::size_t(k * kStencil)];
                for (int dj = -2; dj <= 2; ++dj) {
                    const int qj = j + dj;
                    if (qj < 0 || qj >= f.nv) continue;
                    for (int di = -2; di <= 2; ++di) {
                        const int qi = i + di;
                        if (qi < 0 || qi >= f.nu) continue;
                        const Sym3<S>& b = blocks[stencilSlot(di, dj)];
                        forEachCoarse(c.v, qj, [&](int Qj, double wqj) {
                            forEachCoarse(c.u, qi, [&](int Qi, double wqi) {
                                if (c.pinned[std::size_t(std::int64_t(Qj) * c.nu + Qi)]) return;
                                const int dI = Qi - I, dJ = Qj - J;
                                if (dI < -2 || dI > 2 || dJ < -2 || dJ > 2)
                                    throw std::logic_error("multigrid: coarse stencil radius > 2");
                                row[stencilSlot(dI, dJ)] += b * S(wi * wj * wqi * wqj);
                            });
                        });
                    }
                }
            });
        });
    }
}

// Level l's line factors: this thread's rows (direction 0) and columns (1).
template <typename T>
void CpuMultigrid<T>::smoother(int l, const CycleThreads& threads) {
    Level& g = levels_[std::size_t(l)];
    const int nu = g.nu, nv = g.nv;
    for (int direction = 0; direction < 2; ++direction) {
        const int count = direction == 0 ? nv : nu, m = direction == 0 ? nu : nv;
        const int first = int(std::int64_t(count) * threads.index / threads.count);
        const int last = int(std::int64_t(count) * (threads.index + 1) / threads.count);
        const std::size_t dofs = 3 * std::size_t(m), width = kBand + 1;
        for (int line = first; line < last; ++line) {
            double* f = &g.lines[direction][std::size_t(line) * dofs * width];
            auto entry = [&](std::size_t row, std::size_t col) -> double& {
                return f[row * width + (kBand - (row - col))];
            };
            for (std::size_t e = 0; e < dofs * width; ++e) f[e] = 0;
            for (int a = 0; a < m; ++a) {  // A's lower band: blocks (a, b), b = a − 2 … a
                const std::int64_t k =
                    direction == 0 ? std::int64_t(line) * nu + a : std::int64_t(a) * nu + line;
                for (int b = std::max(0, a - 2); b <= a; ++b) {
                    const int di = direction == 0 ? b - a : 0, dj = direction == 0 ? 0 : b - a;
                    const glm::dmat3 block =
                        g.a[std::size_t(k * kStencil + stencilSlot(di, dj))].matrix();
                    for (int row = 0; row < 3; ++row)
                        for (int col = 0; col < 3; ++col) {
                            const std::size_t R = 3 * std::size_t(a) + std::size_t(row);
                            const std::size_t C = 3 * std::size_t(b) + std::size_t(col);
                            if (C <= R) entry(R, C) = block[col][row];
                        }
                }
            }
            for (std::size_t i = 0; i < dofs; ++i) {  // banded Cholesky in place
                const std::size_t lo = i >= kBand ? i - kBand : 0;
                const double diagonal = entry(i, i);
                for (std::size_t j = lo; j <= i; ++j) {
                    double s = entry(i, j);
                    for (std::size_t q = lo; q < j; ++q)
                        if (j - q <= kBand) s -= entry(i, q) * entry(j, q);
                    // A pivot at or under float's rounding of the stiff blocks (float: the mass
                    // is 1e-7 of h²K at 128², stretch 1e6) is held at 1e-6 of the diagonal.
                    entry(i, j) =
                        i == j ? std::sqrt(std::max(s, 1e-6 * diagonal + 1e-300)) : s / entry(j, j);
                }
            }
        }
    }
}

// One line of level g relaxed: (A_line z_line) = r − (A z − A_line z_line) solved exactly.
template <typename T>
void CpuMultigrid<T>::relaxLine(Level& g, int direction, int line, const Vec3<S>* r, Vec3<S>* z) {
    const int nu = g.nu, nv = g.nv, m = direction == 0 ? nu : nv;
    const std::size_t dofs = 3 * std::size_t(m), width = kBand + 1;
    thread_local std::vector<double> y;
    if (y.size() < dofs) y.resize(dofs);
    const double* f = &g.lines[direction][std::size_t(line) * dofs * width];
    auto entry = [&](std::size_t row, std::size_t col) {
        return f[row * width + (kBand - (row - col))];
    };
    for (int a = 0; a < m; ++a) {
        const int i = direction == 0 ? a : line, j = direction == 0 ? line : a;
        const std::int64_t k = std::int64_t(j) * nu + i;
        Vec3<S> sum(0);
        if (!g.pinned[std::size_t(k)]) {
            sum = r[k];
            const Sym3<S>* row = &g.a[std::size_t(k * kStencil)];
            const int dj0 = std::max(-2, -j), dj1 = std::min(2, nv - 1 - j);
            const int di0 = std::max(-2, -i), di1 = std::min(2, nu - 1 - i);
            for (int dj = dj0; dj <= dj1; ++dj)
                for (int di = di0; di <= di1; ++di) {
                    if (direction == 0 ? dj == 0 : di == 0) continue;  // on the line
                    sum -= row[stencilSlot(di, dj)] * z[k + std::int64_t(dj) * nu + di];
                }
        }
        for (int c = 0; c < 3; ++c) y[3 * std::size_t(a) + std::size_t(c)] = double(sum[c]);
    }
    for (std::size_t i = 0; i < dofs; ++i) {  // L y' = y
        double s = y[i];
        for (std::size_t q = i >= kBand ? i - kBand : 0; q < i; ++q) s -= entry(i, q) * y[q];
        y[i] = s / entry(i, i);
    }
    for (std::size_t i = dofs; i-- > 0;) {  // Lᵀ z = y'
        double s = y[i];
        for (std::size_t q = i + 1; q < std::min(dofs, i + kBand + 1); ++q) s -= entry(q, i) * y[q];
        y[i] = s / entry(i, i);
    }
    for (int a = 0; a < m; ++a) {
        const int i = direction == 0 ? a : line, j = direction == 0 ? line : a;
        const std::int64_t k = std::int64_t(j) * nu + i;
        z[k] = g.pinned[std::size_t(k)]
                   ? Vec3<S>(0)
                   : Vec3<S>(S(y[3 * std::size_t(a)]), S(y[3 * std::size_t(a) + 1]),
                             S(y[3 * std::size_t(a) + 2]));
    }
}

template <typename T>
void CpuMultigrid<T>::linearise(const FineSystem& fine, const CycleThreads& threads) {
    if (threads.index == 0) {
        if (int(probe_.size()) < threads.count) {
            probe_.resize(std::size_t(threads.count));
            probed_.resize(std::size_t(threads.count));
        }
        springs_.clear();
        for (const StencilSpring<T>& s : *fine.springs)
            springs_.push_back({s.di, s.dj, s.indexOffset, S(s.stiffness), S(s.restLength),
                                s.halvedOnBorder, S(s.damping)});
        const std::int64_t n = std::int64_t(fine.nu) * fine.nv;
        if (std::int64_t(inverseMass_.size()) != n) {
            inverseMass_.assign(std::size_t(n), S(0));
            x_.assign(n, Vec3<S>(0));
        }
    }
    threads.sync();  // the double copies' storage is in place
    ProbeSystem system;
    system.nu = fine.nu;
    system.nv = fine.nv;
    system.springs = &springs_;
    system.bending = fine.bending;
    system.x = &x_;
    system.inverseMass = inverseMass_.data();
    system.pinned = fine.pinned;
    system.h = S(fine.h);
    system.drag = S(fine.drag);
    system.springDamping = fine.springDamping;
    system.grabVertex = fine.grabVertex;
    system.grabStiffness = S(fine.grabStiffness);
    {
        const auto [begin, end] = slice(fine.nu, fine.nv, threads);
        for (std::int64_t k = begin; k < end; ++k) {
            x_.set(k, Vec3<S>(positionAt(*fine.x, k)));
            inverseMass_[std::size_t(k)] = S(fine.inverseMass[k]);
        }
    }
    threads.sync();
    probeFine(system, threads);
    threads.sync();
    smoother(0, threads);
    for (int l = 1; l < levels(); ++l) {
        const bool serial = threads.count > 1 && levels_[std::size_t(l)].count() < kSerialBelow;
        if (serial) {
            if (threads.index == 0) {
                for (int m = l; m < levels(); ++m) {
                    galerkin(m, CycleThreads{});
                    smoother(m, CycleThreads{});
                }
            }
            break;
        }
        threads.sync();  // level l − 1 complete
        galerkin(l, threads);
        threads.sync();  // the columns' lines cross every thread's rows
        smoother(l, threads);
    }
    if (threads.index == 0) factorCoarsest();
    threads.sync();
}

// The coarsest stencil as a dense matrix (pinned rows and columns the identity's), factored
// A = L Lᵀ in double.
template <typename T>
void CpuMultigrid<T>::factorCoarsest() {
    const Level& c = levels_.back();
    const std::int64_t n = c.count();
    const std::size_t dofs = 3 * std::size_t(n);
    std::vector<double>& a = cholesky_;
    std::fill(a.begin(), a.end(), 0.0);
    for (std::int64_t k = 0; k < n; ++k) {
        const int i = int(k % c.nu), j = int(k / c.nu);
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
                if (i + di < 0 || i + di >= c.nu || j + dj < 0 || j + dj >= c.nv) continue;
                const std::int64_t q = k + std::int64_t(dj) * c.nu + di;
                const glm::dmat3 b = c.a[std::size_t(k * kStencil + stencilSlot(di, dj))].matrix();
                for (int row = 0; row < 3; ++row)
                    for (int col = 0; col < 3; ++col)
                        a[(3 * std::size_t(k) + std::size_t(row)) * dofs + 3 * std::size_t(q) +
                          std::size_t(col)] = b[col][row];
            }
    }
    for (std::size_t j = 0; j < dofs; ++j) {  // Cholesky–Banachiewicz, lower triangle in place
        const double diagonal = a[j * dofs + j];
        for (std::size_t i = j; i < dofs; ++i) {
            double s = a[i * dofs + j];
            for (std::size_t m = 0; m < j; ++m) s -= a[i * dofs + m] * a[j * dofs + m];
            a[i * dofs + j] =
                i == j ? std::sqrt(std::max(s, 1e-6 * diagonal + 1e-300)) : s / a[j * dofs + j];
        }
    }
}

template <typename T>
void CpuMultigrid<T>::solveCoarsest() {
    Level& c = levels_.back();
    const std::size_t dofs = 3 * std::size_t(c.count());
    const std::vector<double>& a = cholesky_;
    std::vector<double>& y = solve_;
    for (std::size_t i = 0; i < dofs; ++i) {  // L y = r
        double s = double(c.r[i / 3][int(i % 3)]);
        for (std::size_t m = 0; m < i; ++m) s -= a[i * dofs + m] * y[m];
        y[i] = s / a[i * dofs + i];
    }
    for (std::size_t i = dofs; i-- > 0;) {  // Lᵀ z = y
        double s = y[i];
        for (std::size_t m = i + 1; m < dofs; ++m) s -= a[m * dofs + i] * y[m];
        y[i] = s / a[i * dofs + i];
    }
    for (std::size_t i = 0; i < dofs; ++i)
        c.z[i / 3][int(i % 3)] = c.pinned[i / 3] ? S(0) : S(y[i]);
}

template <typename T>
void CpuMultigrid<T>::apply(const std::vector<Vec3<T>>& r, std::vector<Vec3<T>>& z,
                            const CycleThreads& threads) {
    Level& f = levels_[0];
    const auto [begin, end] = slice(f.nu, f.nv, threads);
    for (std::int64_t k = begin; k < end; ++k) f.r[std::size_t(k)] = Vec3<S>(r[std::size_t(k)]);
    threads.sync();
    if (levels() == 1) {  // too small to coarsen: solved exactly (it is the coarsest grid)
        if (threads.index == 0) solveCoarsest();
        threads.sync();
    } else {
        cycle(0, f.r.data(), f.z.data(), threads);  // ends with a sync
    }
    for (std::int64_t k = begin; k < end; ++k) z[std::size_t(k)] = Vec3<T>(f.z[std::size_t(k)]);
    threads.sync();  // the caller's passes read other rows
}

// z = V r on level l (levels_[l + 1] the next coarser one, none on the coarsest).
template <typename T>
void CpuMultigrid<T>::cycle(int l, const Vec3<S>* r, Vec3<S>* z, const CycleThreads& threads) {
    Level& g = levels_[std::size_t(l)];
    if (l + 1 == levels()) {
        if (threads.index == 0) solveCoarsest();
        threads.sync();
        return;
    }
    if (threads.count > 1 && g.count() < kSerialBelow) {  // too small to share: thread 0 alone
        if (threads.index == 0) cycle(l, r, z, CycleThreads{});
        threads.sync();
        return;
    }
    const auto [begin, end] = slice(g.nu, g.nv, threads);
    const int nu = g.nu, nv = g.nv;
    auto residual = [&] {  // t = r − A z on this thread's rows
        for (std::int64_t k = begin; k < end; ++k) {
            const int i = int(k % nu), j = int(k / nu);
            const Sym3<S>* row = &g.a[std::size_t(k * kStencil)];
            Vec3<S> sum = r[k];
            if (!g.pinned[std::size_t(k)]) {
                const int dj0 = std::max(-2, -j), dj1 = std::min(2, nv - 1 - j);
                const int di0 = std::max(-2, -i), di1 = std::min(2, nu - 1 - i);
                for (int dj = dj0; dj <= dj1; ++dj)
                    for (int di = di0; di <= di1; ++di)
                        sum -= row[stencilSlot(di, dj)] * z[k + std::int64_t(dj) * nu + di];
            }
            g.t[std::size_t(k)] = sum;
        }
    };
    // One sweep of line relaxation in one direction, its 5 colours of lines in turn (lines
    // of one colour are 5 apart, out of each other's stencil, so they relax independently).
    auto sweep = [&](int direction, bool forward) {
        const int count = direction == 0 ? nv : nu;
        const int first = int(std::int64_t(count) * threads.index / threads.count);
        const int last = int(std::int64_t(count) * (threads.index + 1) / threads.count);
        for (int c = 0; c < 5; ++c) {
            const int colour = forward ? c : 4 - c;
            for (int line = first + ((colour - first) % 5 + 5) % 5; line < last; line += 5)
                relaxLine(g, direction, line, r, z);
            threads.sync();
        }
    };
    for (std::int64_t k = begin; k < end; ++k) z[k] = Vec3<S>(0);
    threads.sync();
    for (int s = 0; s < kSweeps; ++s) {  // rows, then columns
        sweep(0, true);
        sweep(1, true);
    }
    residual();
    threads.sync();
    Level& c = levels_[std::size_t(l + 1)];
    {  // r_c = Pᵀ t (0 on pinned coarse vertices; t is 0 on pinned fine ones)
        const auto [cb, ce] = slice(c.nu, c.nv, threads);
        for (std::int64_t K = cb; K < ce; ++K) {
            Vec3<S> sum(0);
            if (!c.pinned[std::size_t(K)])
                forEachFine(c.v, int(K / c.nu), [&](int j, double wj) {
                    forEachFine(c.u, int(K % c.nu), [&](int i, double wi) {
                        sum += S(wi * wj) * g.t[std::size_t(std::int64_t(j) * nu + i)];
                    });
                });
            c.r[std::size_t(K)] = sum;
        }
        threads.sync();
    }
    cycle(l + 1, c.r.data(), c.z.data(), threads);  // ends with a sync
    for (std::int64_t k = begin; k < end; ++k) {    // z += P z_c on unpinned vertices
        if (g.pinned[std::size_t(k)]) continue;
        Vec3<S> sum(0);
        forEachCoarse(c.v, int(k / nu), [&](int J, double wj) {
            forEachCoarse(c.u, int(k % nu), [&](int I, double wi) {
                sum += S(wi * wj) * c.z[std::size_t(std::int64_t(J) * c.nu + I)];
            });
        });
        z[k] += sum;
    }
    threads.sync();
    for (int s = 0; s < kSweeps; ++s) {  // the adjoint: columns, then rows, colours reversed
        sweep(1, false);
        sweep(0, false);
    }
}

template class CpuMultigrid<float>;
template class CpuMultigrid<double>;

}  // namespace cloth
