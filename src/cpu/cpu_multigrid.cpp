// The multigrid V-cycle of cpu/cpu_multigrid.h (the hierarchy it runs on:
// cpu_multigrid_build.cpp and cpu_multigrid_galerkin.cpp).
#include "cpu/cpu_multigrid.h"

#include <algorithm>
#include <cmath>

namespace cloth {

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
    const std::int64_t along = direction == 0 ? 1 : nu;  // from one vertex of the line to the next
    for (int a = 0; a < m; ++a) {
        const int i = direction == 0 ? a : line, j = direction == 0 ? line : a;
        const std::int64_t k = std::int64_t(j) * nu + i;
        if (a + kAhead < m)
            for (int slot = 0; slot < kStencil; ++slot)
                if (g.reaches(slot) && (direction == 0 ? slot / 5 != 2 : slot % 5 != 2))
                    g.prefetch(k + kAhead * along, slot);
        Vec3<S> sum(0);
        if (!g.pinned[std::size_t(k)] && g.isInterior(i, j)) {
            sum = r[k];
            g.subtract(sum, k, direction == 0 ? Level::kOffRow : Level::kOffColumn, z);
        } else if (!g.pinned[std::size_t(k)]) {
            sum = r[k];
            const int dj0 = std::max(-2, -j), dj1 = std::min(2, nv - 1 - j);
            const int di0 = std::max(-2, -i), di1 = std::min(2, nu - 1 - i);
            for (int dj = dj0; dj <= dj1; ++dj)
                for (int di = di0; di <= di1; ++di) {
                    const int slot = stencilSlot(di, dj);
                    if ((direction == 0 ? dj == 0 : di == 0) || !g.reaches(slot)) continue;
                    sum -= g.times(k, slot, z[k + std::int64_t(dj) * nu + di]);
                }
        }
        for (int c = 0; c < 3; ++c) y[3 * std::size_t(a) + std::size_t(c)] = double(sum[c]);
    }
    // The substitutions, oldest column first; rows a full band from the line's ends in loops of
    // fixed length, which the compiler unrolls (the same sums in the same order).
    for (std::size_t i = 0; i < dofs; ++i) {  // L y' = y: row i holds columns i − 8 … i
        const double* row = f + i * width;
        double s = y[i];
        if (i >= kBand) {
            const double* older = &y[i - kBand];
            for (std::size_t c = 0; c < kBand; ++c) s -= row[c] * older[c];
        } else {
            for (std::size_t q = 0; q < i; ++q) s -= entry(i, q) * y[q];
        }
        y[i] = s * row[kBand];
    }
    for (std::size_t i = dofs; i-- > 0;) {  // Lᵀ z = y': column i, rows i + 1 … i + 8
        double s = y[i];
        if (i + kBand < dofs) {
            const double* column = f + (i + 1) * width + kBand - 1;  // L(i + 1, i), then 8 apart
            for (std::size_t c = 0; c < kBand; ++c) s -= column[c * kBand] * y[i + 1 + c];
        } else {
            for (std::size_t q = i + 1; q < dofs; ++q) s -= entry(q, i) * y[q];
        }
        y[i] = s * entry(i, i);
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

// (P z_c)_k: vertex k of grid l − 1 from the corners of its cell on grid l.
template <typename T>
Vec3<typename CpuMultigrid<T>::S> CpuMultigrid<T>::prolongAt(int l, std::int64_t k,
                                                             const Vec3<S>* coarse) const {
    const Level& f = levels_[std::size_t(l - 1)];
    const Level& c = levels_[std::size_t(l)];
    const int I = c.u.lower[std::size_t(k % f.nu)], J = c.v.lower[std::size_t(k / f.nu)];
    Vec3<S> sum(0);
    for (int corner = 0; corner < 4; ++corner) {
        const int U = I + (corner & 1), V = J + (corner >> 1);
        if (U >= c.nu || V >= c.nv) continue;
        sum += c.p[4 * std::size_t(k) + std::size_t(corner)] *
               coarse[std::size_t(std::int64_t(V) * c.nu + U)];
    }
    return sum;
}

template <typename T>
std::vector<Vec3<typename CpuMultigrid<T>::S>> CpuMultigrid<T>::interpolate(
    int l, const std::vector<Vec3<S>>& coarse) const {
    std::vector<Vec3<S>> fine(std::size_t(levels_[std::size_t(l - 1)].count()));
    for (std::size_t k = 0; k < fine.size(); ++k)
        fine[k] = prolongAt(l, std::int64_t(k), coarse.data());
    return fine;
}

template <typename T>
std::vector<Vec3<typename CpuMultigrid<T>::S>> CpuMultigrid<T>::stencilTimes(
    int l, const std::vector<Vec3<S>>& w) const {
    const Level& g = levels_[std::size_t(l)];
    std::vector<Vec3<S>> out(w.size(), Vec3<S>(0));
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const int i = int(k % g.nu), j = int(k / g.nu);
        for (int dj = std::max(-2, -j); dj <= std::min(2, g.nv - 1 - j); ++dj)
            for (int di = std::max(-2, -i); di <= std::min(2, g.nu - 1 - i); ++di)
                out[std::size_t(k)] += g.block(k, stencilSlot(di, dj)) *
                                       w[std::size_t(k + std::int64_t(dj) * g.nu + di)];
    }
    return out;
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
            Vec3<S> sum = r[k];
            if (!g.pinned[std::size_t(k)] && g.isInterior(i, j)) {
                g.subtract(sum, k, Level::kAll, z);
            } else if (!g.pinned[std::size_t(k)]) {
                const int dj0 = std::max(-2, -j), dj1 = std::min(2, nv - 1 - j);
                const int di0 = std::max(-2, -i), di1 = std::min(2, nu - 1 - i);
                for (int dj = dj0; dj <= dj1; ++dj)
                    for (int di = di0; di <= di1; ++di)
                        if (g.reaches(stencilSlot(di, dj)))
                            sum -=
                                g.times(k, stencilSlot(di, dj), z[k + std::int64_t(dj) * nu + di]);
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
            const int I = int(K % c.nu), J = int(K / c.nu);
            if (!c.pinned[std::size_t(K)])
                forEachCellOf(c.v, J, [&](int Cv) {
                    forEachCellOf(c.u, I, [&](int Cu) {
                        const std::size_t corner = std::size_t((I - Cu) + 2 * (J - Cv));
                        for (int j = c.v.first[std::size_t(Cv)]; j < c.v.first[std::size_t(Cv + 1)];
                             ++j)
                            for (int i = c.u.first[std::size_t(Cu)];
                                 i < c.u.first[std::size_t(Cu + 1)]; ++i) {
                                const std::size_t k = std::size_t(std::int64_t(j) * nu + i);
                                sum += g.t[k] * c.p[4 * k + corner];  // (Pᵀ)_Kk t_k = t_kᵀ P_kK
                            }
                    });
                });
            c.r[std::size_t(K)] = sum;
        }
        threads.sync();
    }
    cycle(l + 1, c.r.data(), c.z.data(), threads);  // ends with a sync
    for (std::int64_t k = begin; k < end; ++k)      // z += P z_c on unpinned vertices
        if (!g.pinned[std::size_t(k)]) z[k] += prolongAt(l + 1, k, c.z.data());
    threads.sync();
    for (int s = 0; s < kSweeps; ++s) {  // the adjoint: columns, then rows, colours reversed
        sweep(1, false);
        sweep(0, false);
    }
}

template class CpuMultigrid<float>;
template class CpuMultigrid<double>;

}  // namespace cloth