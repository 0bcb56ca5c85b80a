// The multigrid hierarchy of cpu/cpu_multigrid.h, rebuilt every step: the grids' axes, the fine
// stencil assembled from the system's terms, the line factors and the coarsest factor (P and the
// Galerkin products: cpu_multigrid_galerkin.cpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cpu/cpu_multigrid.h"

namespace cloth {
template <typename T>
typename CpuMultigrid<T>::Axis CpuMultigrid<T>::coarsen(int n) {
    Axis a;
    const int coarse = coarsenedCount(n);
    for (int I = 0; I < coarse; ++I) a.at.push_back(std::min(2 * I, n - 1));
    for (int i = 0; i < n; ++i) {
        if (coarse == 1) {
            a.lower.push_back(0);
            a.weight.push_back(0);
            continue;
        }
        int I = 0;  // the cell: the last one whose lower corner lies below i
        while (I + 2 < coarse && a.at[std::size_t(I + 1)] < i) ++I;
        const int lo = a.at[std::size_t(I)], hi = a.at[std::size_t(I + 1)];
        a.lower.push_back(I);
        a.weight.push_back(S(i - lo) / S(hi - lo));
    }
    a.first.push_back(0);
    for (int i = 1; i < n; ++i)
        if (a.lower[std::size_t(i)] != a.lower[std::size_t(i - 1)]) a.first.push_back(i);
    a.first.push_back(n);
    return a;
}

template <typename T>
void CpuMultigrid<T>::configure(int nu, int nv, int threads, bool fineOnly) {
    levels_.clear();
    configured_ = true;
    fineOnly_ = fineOnly;
    std::vector<MultigridLevel> sizes = multigridLevels(nu, nv);
    if (fineOnly) sizes.resize(1);
    for (const MultigridLevel& size : sizes) {
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
        if (l == 0) {
            level.place.fill(-1);
            for (int e = 0; e < kFineBlocks; ++e)
                level.place[std::size_t(stencilSlot(kFinePlaces[e][0], kFinePlaces[e][1]))] =
                    std::int8_t(e);
            level.perVertex = kFineBlocks;
            level.symmetric.assign(n * kFineBlocks, Sym3<S>{});
        } else {
            level.place = slotOrder();
            level.a.assign(n * kStencil, Block(0));
        }
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
                const int slot = stencilSlot(di, dj);
                if (!level.reaches(slot)) continue;
                const typename Level::Reach e{level.place[std::size_t(slot)],
                                              std::int64_t(dj) * level.nu + di};
                level.interior[Level::kAll].push_back(e);
                if (dj != 0) level.interior[Level::kOffRow].push_back(e);
                if (di != 0) level.interior[Level::kOffColumn].push_back(e);
            }
        level.x.assign(n, Vec3<S>(0));
        if (l > 0) level.p.assign(4 * std::size_t(levels_[l - 1].count()), Block(0));
        level.lines[0].configure(level.nv, level.nu, threads);
        level.lines[1].configure(level.nu, level.nv, threads);
        level.pinned.assign(n, 0);
        level.t.assign(n, Vec3<S>(0));
        level.r.assign(n, Vec3<S>(0));
        level.z.assign(n, Vec3<S>(0));
    }
    product_.assign(levels_.size() > 1 ? 16 * std::size_t(levels_[0].count()) : 0, Block(0));
    // (The fine stencil alone has no coarsest grid: its dense factor would be (3n)² values.)
    const std::size_t dofs = fineOnly ? 0 : 3 * std::size_t(levels_.back().count());
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

// The fine grid's stencil, assembled block by block from the system's terms (model/
// implicit_system.h): per spring s from k to q, a = h² J_s + h D_s on the diagonal and −a at q;
// the bending Hessian's constant weights W_kq (minus the force at k of a unit field at q) times
// h² I; the mass, drag and grab spring on the diagonal. A pinned column is left out (p = 0
// there), a pinned row is the identity's. `Multigrid.FineStencilIsTheSystemsMatrix` holds it to
// the matrix-free product.
template <typename T>
void CpuMultigrid<T>::assembleFine(const FineSystemS& fine, const CycleThreads& threads) {
    Level& level = levels_[0];
    const int nu = level.nu, nv = level.nv;
    const S h = fine.h, h2 = h * h;
    auto bendWeight = [&](int i, int j, int qi, int qj) {
        auto unit = [&](int a, int b) { return Vec3<S>(a == qi && b == qj ? 1 : 0); };
        return -bendingForce<S>(fine.bending, i, j, unit).x;
    };
    const auto [begin, end] = slice(nu, nv, threads);
    for (std::int64_t k = begin; k < end; ++k) {
        auto blockAt = [&](int di, int dj) -> Sym3<S>& {
            return level.symmetric[level.at(k, stencilSlot(di, dj))];
        };
        for (const auto& o : kFinePlaces) blockAt(o[0], o[1]) = {};
        level.pinned[std::size_t(k)] = fine.pinned[k];
        Sym3<S>& diagonal = blockAt(0, 0);
        if (fine.pinned[k]) {
            diagonal = Sym3<S>::identity(1);
            continue;
        }
        const int i = int(k % nu), j = int(k / nu);
        const Vec3<S> xk = x_.get(k);
        diagonal = Sym3<S>::identity(fine.drag / fine.inverseMass[k]);
        for (const StencilSpring<S>& s : springs_) {
            const int qi = i + s.di, qj = j + s.dj;
            if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
            const std::int64_t q = k + s.indexOffset;
            const SpringBlocks<S> b =
                springBlocks(s, xk, x_.get(q), i, j, nu, nv, fine.springDamping);
            Sym3<S> a = b.stiffness * h2;
            if (fine.springDamping) a += b.damping * h;
            diagonal += a;
            if (!fine.pinned[q]) blockAt(s.di, s.dj) += a * S(-1);
        }
        if (fine.bending.active())
            for (const auto& o : kBendReach) {
                const int qi = i + o[0], qj = j + o[1];
                if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
                if (fine.pinned[std::int64_t(qj) * nu + qi]) continue;
                blockAt(o[0], o[1]).addDiagonal(h2 * bendWeight(i, j, qi, qj));
            }
        if (k == fine.grabVertex) diagonal.addDiagonal(h2 * fine.grabStiffness);
    }
}

// Level l's line factors: this thread's rows (direction 0) and columns (1).
template <typename T>
void CpuMultigrid<T>::smoother(int l, const CycleThreads& threads) {
    Level& g = levels_[std::size_t(l)];
    const int nu = g.nu;
    for (int direction = 0; direction < 2; ++direction) {
        Lines& lines = g.lines[direction];
        const int m = lines.length;
        const std::size_t dofs = lines.dofs(), width = kBand + 1;
        for (int colour = 0; colour < 5; ++colour) {
            const auto [first, last] = lines.pairs(colour, threads);
            for (int p = first; p < last; ++p)
                for (int lane = 0; lane < kLanes; ++lane) {
                    const int line = lines.line(p, lane);
                    if (line < 0) continue;
                    double* f = lines.pair(p) + lane;
                    auto entry = [&](std::size_t row, std::size_t col) -> double& {
                        return f[(row * width + (kBand - (row - col))) * kLanes];
                    };
                    for (std::size_t e = 0; e < dofs * width; ++e) f[e * kLanes] = 0;
                    for (int a = 0; a < m; ++a) {  // A's lower band: blocks (a, b), b = a − 2 … a
                        const std::int64_t k = direction == 0 ? std::int64_t(line) * nu + a
                                                              : std::int64_t(a) * nu + line;
                        for (int b = std::max(0, a - 2); b <= a; ++b) {
                            const int di = direction == 0 ? b - a : 0,
                                      dj = direction == 0 ? 0 : b - a;
                            const Block block = g.block(k, stencilSlot(di, dj));
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
                            // A pivot at or under float's rounding of the stiff blocks (float: the
                            // mass is 1e-7 of h²K at 128², stretch 1e6) is held at 1e-6 of the
                            // diagonal. The diagonal is kept as its reciprocal: the substitutions
                            // multiply.
                            entry(i, j) = i == j
                                              ? 1 / std::sqrt(std::max(s, 1e-6 * diagonal + 1e-300))
                                              : s * entry(j, j);
                        }
                    }
                }
        }
    }
}

template <typename T>
void CpuMultigrid<T>::linearise(const FineSystem& fine, const CycleThreads& threads) {
    if (threads.index == 0) {
        springs_.clear();
        for (const StencilSpring<T>& s : *fine.springs)
            springs_.push_back({s.di, s.dj, s.indexOffset, S(s.stiffness), S(s.restLength),
                                s.halvedOnBorder, S(s.damping)});
        static_assert(stencilIsPlaced(), "a spring or the bending reaches past the fine records");
        static_assert(placesAreTheDiamond(), "the fine records differ from the GPU's reach");
        const std::int64_t n = std::int64_t(fine.nu) * fine.nv;
        if (std::int64_t(inverseMass_.size()) != n) {
            inverseMass_.assign(std::size_t(n), S(0));
            x_.assign(n, Vec3<S>(0));
        }
    }
    threads.sync();  // the double copies' storage is in place
    FineSystemS system;
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
            levels_[0].x[std::size_t(k)] = x_.get(k);
            inverseMass_[std::size_t(k)] = S(fine.inverseMass[k]);
        }
    }
    threads.sync();
    assembleFine(system, threads);
    if (fine.contacts) {  // the contacts in the solve, as stiff normal springs (see below)
        Level& level = levels_[0];
        const auto [begin, end] = slice(fine.nu, fine.nv, threads);
        for (std::int64_t k = begin; k < end; ++k) {
            const Vec3<S> n(fine.contacts[k].normal);
            if (fine.pinned[k] || n == Vec3<S>(0)) continue;
            Sym3<S>& d = level.symmetric[level.at(k, stencilSlot(0, 0))];
            const S penalty = kContactPenalty * (d.xx + d.yy + d.zz) / 3;
            if (fine.contacts[k].held) {  // fixed in every direction
                d.xx += penalty;
                d.yy += penalty;
                d.zz += penalty;
            } else {
                d.addOuter(penalty, n);
            }
        }
    }
    threads.sync();
    if (fineOnly_) return;
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

template <typename T>
void CpuMultigrid<T>::fineGrid(BlockGrid& out) const {
    const Level& fine = levels_[0];
    out.resize(fine.nu, fine.nv, 3);
    for (std::int64_t k = 0; k < fine.count(); ++k) {
        for (int slot = 0; slot < kStencil; ++slot) {
            if (!fine.reaches(slot)) continue;
            const Block b = fine.block(k, slot);
            double* to = out.block(k, slot);
            for (int row = 0; row < 3; ++row)
                for (int col = 0; col < 3; ++col) to[3 * col + row] = b[col][row];
        }
        if (fine.pinned[std::size_t(k)]) std::fill_n(&out.fixed[3 * std::size_t(k)], 3, 1);
    }
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
                const Block b = c.block(k, stencilSlot(di, dj));
                for (int row = 0; row < 3; ++row)
                    for (int col = 0; col < 3; ++col)
                        a[(3 * std::size_t(k) + std::size_t(row)) * dofs + 3 * std::size_t(q) +
                          std::size_t(col)] = b[col][row];
            }
    }
    denseCholesky(a.data(), dofs, 1e-6);
}

// cpu_multigrid.h declares the class instantiations extern: this file's members are instantiated
// here, P's and the Galerkin products' in cpu_multigrid_galerkin.cpp, the cycle's in
// cpu_multigrid.cpp.
#define CLOTH_INSTANTIATE(T)                                                                    \
    template CpuMultigrid<T>::Axis CpuMultigrid<T>::coarsen(int);                               \
    template void CpuMultigrid<T>::configure(int, int, int, bool);                              \
    template std::pair<std::int64_t, std::int64_t> CpuMultigrid<T>::slice(int, int,             \
                                                                          const CycleThreads&); \
    template void CpuMultigrid<T>::assembleFine(const FineSystemS&, const CycleThreads&);       \
    template void CpuMultigrid<T>::smoother(int, const CycleThreads&);                          \
    template void CpuMultigrid<T>::linearise(const FineSystem&, const CycleThreads&);           \
    template void CpuMultigrid<T>::factorCoarsest();                                            \
    template void CpuMultigrid<T>::fineGrid(BlockGrid&) const;
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
