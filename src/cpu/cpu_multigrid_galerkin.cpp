// The multigrid hierarchy's coarse grids (cpu/cpu_multigrid.h), rebuilt every step from the
// finer one: the prolongation P (with its rotation term) and the Galerkin product Pᵀ A P.
#include "cpu/cpu_multigrid.h"

namespace cloth {
namespace {

// The cross-product matrix: cross(v, y) = crossMatrix(v) y.
template <typename M, typename V>
M crossMatrix(const V& v) {
    return M(0, v.z, -v.y, -v.z, 0, v.x, v.y, -v.x, 0);
}

}  // namespace

// Level l's P on this thread's rows of level l − 1 (docs/integrators.md, "Preconditioners"). A
// fine vertex k in the coarse cell with corners X_c takes the bilinear blend Σ w_c z_c of the
// corners' corrections plus the rotation the cell's corrections describe, ω × d_k, where
// d_k = x_k − Σ w_c X_c is how far the curved sheet lies off the blended corners and ω is
// the least-squares rotation of the cell's two mean edge differences (exact for a rigid motion,
// z = ω × X + t, which P then carries to every fine vertex exactly). Bilinear interpolation alone
// moves a sagged vertex by ω × (Σ w_c X_c), not ω × x_k: on a curved sheet it stretches the stiff
// membrane under the rotations the soft bending modes are made of.
template <typename T>
void CpuMultigrid<T>::prolongation(int l, const CycleThreads& threads) {
    const Level& f = levels_[std::size_t(l - 1)];
    Level& c = levels_[std::size_t(l)];
    const auto [begin, end] = slice(f.nu, f.nv, threads);
    const bool cells = c.nu > 1 && c.nv > 1;  // a rotation needs two directions
    for (std::int64_t k = begin; k < end; ++k) {
        const int i = int(k % f.nu), j = int(k / f.nu);
        const int I = c.u.lower[std::size_t(i)], J = c.v.lower[std::size_t(j)];
        const S wu = c.u.weight[std::size_t(i)], wv = c.v.weight[std::size_t(j)];
        const S w[4] = {(1 - wu) * (1 - wv), wu * (1 - wv), (1 - wu) * wv, wu * wv};
        Block* p = &c.p[4 * std::size_t(k)];
        for (int corner = 0; corner < 4; ++corner) p[corner] = Block(w[corner]);
        if (!cells) continue;
        Vec3<S> X[4], blend(0);
        for (int corner = 0; corner < 4; ++corner) {
            X[corner] = c.x[std::size_t(std::int64_t(J + (corner >> 1)) * c.nu + I + (corner & 1))];
            blend += w[corner] * X[corner];
        }
        const Vec3<S> d = f.x[std::size_t(k)] - blend;
        const Vec3<S> a = S(0.5) * ((X[1] - X[0]) + (X[3] - X[2]));
        const Vec3<S> b = S(0.5) * ((X[2] - X[0]) + (X[3] - X[1]));
        const S aa = glm::dot(a, a), bb = glm::dot(b, b);
        // ω minimises |ω × a − Δz_a|² + |ω × b − Δz_b|²: (|a|² + |b|² − a aᵀ − b bᵀ) ω =
        // a × Δz_a + b × Δz_b, with Δz_a, Δz_b the cell's mean differences along a and b.
        const Block normal = Block(aa + bb) - glm::outerProduct(a, a) - glm::outerProduct(b, b);
        const S det = glm::determinant(normal);
        if (!(det > S(1e-12) * (aa + bb) * (aa + bb) * (aa + bb))) continue;  // a degenerate cell
        const Block inverse = glm::inverse(normal);
        const Block ca = crossMatrix<Block>(a), cb = crossMatrix<Block>(b);
        const Block cd = crossMatrix<Block>(d);
        for (int corner = 0; corner < 4; ++corner) {
            const S sa = (corner & 1) ? S(0.5) : S(-0.5), sb = (corner >> 1) ? S(0.5) : S(-0.5);
            // ω × d = −d × ω
            p[corner] -= cd * (inverse * (sa * ca + sb * cb));
        }
    }
}

// Level l's stencil A_l = Pᵀ (A_{l−1} P) in two passes: (A P)_kQ = Σ_q A_kq P_qQ on this thread's
// rows of level l − 1, then (A_l)_KQ = Σ_k P_kKᵀ (A P)_kQ on its coarse rows over the fine
// vertices k in the cells with corner K. Pinned vertices on either grid take no part.
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
        c.x[std::size_t(K)] = f.x[std::size_t(centre)];
    }
    threads.sync();  // the pins and positions of the neighbours' rows
    prolongation(l, threads);
    threads.sync();  // P's rows of the neighbours
    const auto [fineBegin, fineEnd] = slice(f.nu, f.nv, threads);
    for (std::int64_t k = fineBegin; k < fineEnd; ++k) {
        Block* out = &product_[16 * std::size_t(k)];
        for (int s = 0; s < 16; ++s) out[s] = Block(0);
        if (f.pinned[std::size_t(k)]) continue;
        const int i = int(k % f.nu), j = int(k / f.nu);
        const int cellU = c.u.lower[std::size_t(i)], cellV = c.v.lower[std::size_t(j)];
        for (int dj = -2; dj <= 2; ++dj) {
            const int qj = j + dj;
            if (qj < 0 || qj >= f.nv) continue;
            for (int di = -2; di <= 2; ++di) {
                const int qi = i + di;
                if (qi < 0 || qi >= f.nu) continue;
                const std::int64_t q = std::int64_t(qj) * f.nu + qi;
                if (f.pinned[std::size_t(q)] || !f.reaches(stencilSlot(di, dj))) continue;
                const Block a = f.block(k, stencilSlot(di, dj));
                const int Qi = c.u.lower[std::size_t(qi)], Qj = c.v.lower[std::size_t(qj)];
                for (int cq = 0; cq < 4; ++cq) {
                    const int U = Qi + (cq & 1), V = Qj + (cq >> 1);
                    if (U >= c.nu || V >= c.nv) continue;
                    const Block& pq = c.p[4 * std::size_t(q) + std::size_t(cq)];
                    if (pq == Block(0) || c.pinned[std::size_t(std::int64_t(V) * c.nu + U)])
                        continue;
                    const int su = U - cellU + 1, sv = V - cellV + 1;
                    if (su < 0 || su > 3 || sv < 0 || sv > 3)
                        throw std::logic_error("multigrid: P reaches past the cell's neighbours");
                    out[su + 4 * sv] += a * pq;
                }
            }
        }
    }
    threads.sync();  // the products of the neighbours' rows
    for (std::int64_t K = begin; K < end; ++K) {
        Block* row = &c.a[std::size_t(K * kStencil)];
        for (int o = 0; o < kStencil; ++o) row[o] = Block(0);
        if (c.pinned[std::size_t(K)]) {
            row[stencilSlot(0, 0)] = Block(1);
            continue;
        }
        const int I = int(K % c.nu), J = int(K / c.nu);
        forEachCellOf(c.v, J, [&](int Cv) {
            forEachCellOf(c.u, I, [&](int Cu) {
                const int corner = (I - Cu) + 2 * (J - Cv);
                for (int j = c.v.first[std::size_t(Cv)]; j < c.v.first[std::size_t(Cv + 1)]; ++j)
                    for (int i = c.u.first[std::size_t(Cu)]; i < c.u.first[std::size_t(Cu + 1)];
                         ++i) {
                        const std::int64_t k = std::int64_t(j) * f.nu + i;
                        if (f.pinned[std::size_t(k)]) continue;
                        const Block& pk = c.p[4 * std::size_t(k) + std::size_t(corner)];
                        if (pk == Block(0)) continue;
                        const Block pkT = glm::transpose(pk);
                        const Block* product = &product_[16 * std::size_t(k)];
                        for (int s = 0; s < 16; ++s) {
                            const int dI = Cu - 1 + (s & 3) - I, dJ = Cv - 1 + (s >> 2) - J;
                            if (product[s] == Block(0)) continue;
                            if (dI < -2 || dI > 2 || dJ < -2 || dJ > 2)
                                throw std::logic_error("multigrid: coarse stencil radius > 2");
                            row[stencilSlot(dI, dJ)] += pkT * product[s];
                        }
                    }
            });
        });
    }
}

// cpu_multigrid.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                               \
    template void CpuMultigrid<T>::prolongation(int, const CycleThreads&); \
    template void CpuMultigrid<T>::galerkin(int, const CycleThreads&);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
