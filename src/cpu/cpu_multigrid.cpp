// The multigrid V-cycle of cpu/cpu_multigrid.h (the hierarchy it runs on:
// cpu_multigrid_build.cpp and cpu_multigrid_galerkin.cpp).
#include "cpu/cpu_multigrid.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace cloth {

// Line `line` of level g's right-hand side: y = r − (A z − A_line z_line) on its unknowns.
template <typename T>
void CpuMultigrid<T>::lineRightHandSide(const Level& g, int direction, int line, const Vec3<S>* r,
                                        const Vec3<S>* z, double* y, int lane) {
    const int nu = g.nu, nv = g.nv, m = direction == 0 ? nu : nv;
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
        for (int c = 0; c < 3; ++c)
            y[(3 * std::size_t(a) + std::size_t(c)) * kLanes + lane] = sum[c];
    }
}

namespace {

// Two doubles, one per lane of a pair: GCC's vector extension, element-wise IEEE arithmetic.
using Pair = double __attribute__((vector_size(16)));
Pair load(const double* at) {
    Pair v;
    std::memcpy(&v, at, sizeof v);
    return v;
}
void store(double* at, Pair v) {
    std::memcpy(at, &v, sizeof v);
}

// L Lᵀ y = y for kPairs pairs of lines of one length (factors f, right-hand sides y, both
// interleaved by lane). Each line's substitutions, oldest column first, are a chain of dependent
// rows; a pair's two lines step together in one vector, and two pairs' chains interleave in the
// core. Rows a full band from the line's ends run in loops of fixed length, which the compiler
// unrolls. Each line's sums are those of the line alone, in its order: the same bits.
template <int kPairs, std::size_t kBand>
void substitutePairs(const double* const* f, double* const* y, std::size_t dofs) {
    constexpr std::size_t width = kBand + 1;
    auto entry = [&](int p, std::size_t row, std::size_t col) {
        return load(f[p] + 2 * (row * width + (kBand - (row - col))));
    };
    for (std::size_t i = 0; i < dofs; ++i) {  // L y' = y: row i holds columns i − 8 … i
        for (int p = 0; p < kPairs; ++p) {
            const double* row = f[p] + 2 * i * width;
            double* yp = y[p];
            Pair s = load(yp + 2 * i);
            if (i >= kBand) {
                const double* older = yp + 2 * (i - kBand);
                for (std::size_t c = 0; c < kBand; ++c)
                    s -= load(row + 2 * c) * load(older + 2 * c);
            } else {
                for (std::size_t q = 0; q < i; ++q) s -= entry(p, i, q) * load(yp + 2 * q);
            }
            store(yp + 2 * i, s * load(row + 2 * kBand));
        }
    }
    for (std::size_t i = dofs; i-- > 0;) {  // Lᵀ z = y': column i, rows i + 1 … i + 8
        for (int p = 0; p < kPairs; ++p) {
            double* yp = y[p];
            Pair s = load(yp + 2 * i);
            if (i + kBand < dofs) {
                // L(i + 1 + c, i) lies c kBand entries after L(i + 1, i).
                const double* column = f[p] + 2 * ((i + 1) * width + kBand - 1);
                const double* newer = yp + 2 * (i + 1);
                for (std::size_t c = 0; c < kBand; ++c)
                    s -= load(column + 2 * c * kBand) * load(newer + 2 * c);
            } else {
                for (std::size_t q = i + 1; q < dofs; ++q) s -= entry(p, q, i) * load(yp + 2 * q);
            }
            store(yp + 2 * i, s * entry(p, i, i));
        }
    }
}

}  // namespace

template <typename T>
void CpuMultigrid<T>::relaxPairs(Level& g, int direction, int first, int last, const Vec3<S>* r,
                                 Vec3<S>* z) {
    static_assert(kLanes == 2, "substitutePairs steps two lanes");
    const Lines& lines = g.lines[direction];
    const std::size_t dofs = lines.dofs();
    thread_local std::vector<double> scratch;
    if (scratch.size() < 2 * kLanes * dofs) scratch.resize(2 * kLanes * dofs);
    for (int p = first; p < last; p += 2) {
        const int pairs = std::min(2, last - p);
        const double* f[2] = {lines.pair(p), pairs > 1 ? lines.pair(p + 1) : nullptr};
        double* y[2] = {&scratch[0], &scratch[kLanes * dofs]};
        for (int q = 0; q < pairs; ++q)
            for (int lane = 0; lane < kLanes; ++lane) {
                const int line = lines.line(p + q, lane);
                if (line >= 0) {
                    lineRightHandSide(g, direction, line, r, z, y[q], lane);
                } else {  // the last pair's empty lane: its factor is 0, and so its values
                    for (std::size_t e = 0; e < dofs; ++e) y[q][e * kLanes + std::size_t(lane)] = 0;
                }
            }
        if (pairs == 2)
            substitutePairs<2, kBand>(f, y, dofs);
        else
            substitutePairs<1, kBand>(f, y, dofs);
        for (int q = 0; q < pairs; ++q)
            for (int lane = 0; lane < kLanes; ++lane) {
                const int line = lines.line(p + q, lane);
                if (line < 0) continue;
                for (int a = 0; a < lines.length; ++a) {
                    const int i = direction == 0 ? a : line, j = direction == 0 ? line : a;
                    const std::int64_t k = std::int64_t(j) * g.nu + i;
                    const double* v = &y[q][3 * std::size_t(a) * kLanes + std::size_t(lane)];
                    z[k] = g.pinned[std::size_t(k)]
                               ? Vec3<S>(0)
                               : Vec3<S>(S(v[0]), S(v[kLanes]), S(v[2 * kLanes]));
                }
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
    const auto rows = slice(g.nu, g.nv, threads);  // not a structured binding: lambdas use it
    const std::int64_t begin = rows.first, end = rows.second;
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
        for (int c = 0; c < 5; ++c) {
            const int colour = forward ? c : 4 - c;
            const auto [first, last] = g.lines[direction].pairs(colour, threads);
            relaxPairs(g, direction, first, last, r, z);
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