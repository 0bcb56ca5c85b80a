// vbd's translation levels on the CPU (docs/integrators.md "The translation's levels"): the
// translation's Newton step (cpu_vbd_translation.cpp) on each block of the sheet cut into 2^l × 2^l
// equal parts, coarse to fine, before the first sweep, where the springs that leave a block join
// the pins'.
//
// A block's problem sums its free vertices' own terms (vbdTranslationTerms) and those springs.
// Most vertices' own terms are linear in their displacement (inertia and drag; a contact's hold
// is constant): those are summed once a step per row and finest block column (vbdLevelOwnRow),
// and every shift and push after updates the sums (vbdShiftRow), so a level visits only the
// vertices near its blocks' edges and those whose terms are not linear (friction, the grab).
#include <algorithm>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_vbd_sums.h"
#include "model/vbd_lane.h"
#include "model/vbd_local.h"

namespace cloth {

using vbd_sums::addLane;
using vbd_sums::kMass;
using vbd_sums::kOwn;
using vbd_sums::kSums;

// Row j's own sums of its linear vertices (vbdLinearOwn), one kOwn-set per finest block column:
// vbdTranslationTerms' lane, Σ m/h² and Σ (m/h² + m c/h); whether the row has a vertex that is
// not linear.
template <typename T>
void CpuSolver<T>::vbdLevelOwnRow(int j) {
    const int nu = grid_.nu, finest = finestColumn_[std::size_t(nu)];
    double* own = ownRows_.data() + std::size_t(j) * std::size_t(finest) * kOwn;
    std::fill(own, own + std::size_t(finest) * kOwn, 0.0);
    bool nonlinear = false;
    for (int i = 0; i < nu; ++i) {
        const std::int64_t k = std::int64_t(j) * nu + i;
        if (pinned_[k]) continue;
        if (!vbdLinearOwn(k, phases_.active() ? phases_.at(i, j) : k)) {
            nonlinear = true;
            continue;
        }
        VbdLane<double> a{};
        double* o = own + finestColumn_[std::size_t(i)] * kOwn;
        o[kMass] += vbdTranslationTerms(i, j, k, a);
        addLane(a, o);
        o[kSums] += vbdInertiaDrag(k);
    }
    rowNonlinear_[std::size_t(j)] = nonlinear;
}

// Row j's part of the block [i0, i1) × [j0, j1)'s problem: its linear vertices' own sums, the
// other free vertices' own terms, and the springs to vertices outside the block or pinned (seen
// from the free vertex; those inside cancel). A spring reaches r = springReach_ cells (2 with bend
// springs, 1 for a material): a vertex r or more from the block's edges, with no pin within r rows
// (`pinsNear` false), has none.
template <typename T>
void CpuSolver<T>::vbdBlockRow(int j, int i0, int i1, int j0, int j1, bool pinsNear,
                               double* out) const {
    const int nu = grid_.nu, nv = grid_.nv, finest = finestColumn_[std::size_t(nu)];
    const double* own = ownRows_.data() + std::size_t(j) * std::size_t(finest) * kOwn;
    for (int e = 0; e < kSums; ++e) out[e] = 0;
    for (int c = finestColumn_[std::size_t(i0)]; c < finestColumn_[std::size_t(i1)]; ++c)
        for (int e = 0; e < kSums; ++e) out[e] += own[c * kOwn + e];
    const int reach = springReach_;
    const bool edgeRow = pinsNear || j - j0 < reach || j1 - 1 - j < reach;
    const auto visit = [&](int i) {
        const std::int64_t k = std::int64_t(j) * nu + i;
        if (pinned_[k]) return;
        VbdLane<double> a{};
        if (!vbdLinearOwn(k, phases_.active() ? phases_.at(i, j) : k))
            out[kMass] += vbdTranslationTerms(i, j, k, a);
        if (edgeRow || i - i0 < reach || i1 - 1 - i < reach) {
            const glm::dvec3 xk(x_.get(k));
            for (const StencilSpring<T>& s : springs_) {
                const int qi = i + s.di, qj = j + s.dj;
                if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
                const std::int64_t q = std::int64_t(qj) * nu + qi;
                if (qi >= i0 && qi < i1 && qj >= j0 && qj < j1 && !pinned_[q]) continue;
                const glm::dvec3 e = glm::dvec3(x_.get(q)) - xk;
                vbdSpringLane(e.x, e.y, e.z, double(stiffnessAt(s, i, j, nu, nv)),
                              double(s.restLength), a);
            }
        }
        addLane(a, out);
    };
    if (edgeRow || rowNonlinear_[std::size_t(j)]) {
        for (int i = i0; i < i1; ++i) visit(i);
        return;
    }
    const int left = std::min(i1, i0 + reach);  // the columns within reach of the edges
    for (int i = i0; i < left; ++i) visit(i);
    for (int i = std::max(left, i1 - reach); i < i1; ++i) visit(i);
}

// The translation's levels, before the first sweep: for each level, coarse to fine, and each of
// its four colours of blocks (no two blocks of a colour side by side), the threads share the
// colour's rows evenly (not by band: at the first level a colour's rows are half the sheet's),
// sum each row's part of each block, then take each block's Newton step from all of that block's
// rows, in order, and apply it to their own rows (vbdTranslate's, per block). With phases the
// levels move x_ and the copy's displacements; the copy's positions take x_ once after them.
template <typename T>
void CpuSolver<T>::vbdTranslateLevels(const Band& band, const Team& team) {
    const int nu = grid_.nu, nv = grid_.nv, finest = vbdLevelParts(translationLevels_, nu, nv);
    for (int j = band.rowBegin; j < band.rowEnd; ++j) {
        const auto row = pinned_.begin() + std::int64_t(j) * nu;
        rowPinned_[std::size_t(j)] = std::find(row, row + nu, std::uint8_t(1)) != row + nu;
        vbdLevelOwnRow(j);
    }
    team.sync();
    const auto pinsNear = [&](int j) {
        for (int r = std::max(0, j - springReach_); r <= std::min(nv - 1, j + springReach_); ++r)
            if (rowPinned_[std::size_t(r)]) return true;
        return false;
    };
    const int self = int(&band - bands_.data()), threads = int(bands_.size());
    for (int parts = 2; parts <= finest; parts *= 2)
        for (int colour = 0; colour < 4; ++colour) {
            const auto rows = [&](int b) { return b * nv / parts; };
            const auto columns = [&](int b) { return b * nu / parts; };
            // This thread's share [first, last) of the colour's rows, counted over its blocks.
            int total = 0;
            for (int bj = colour / 2; bj < parts; bj += 2) total += rows(bj + 1) - rows(bj);
            const int first = int(std::int64_t(total) * self / threads);
            const int last = int(std::int64_t(total) * (self + 1) / threads);
            // f(bj, j0, j1) on each block row bj's part [j0, j1) of this thread's share.
            const auto forShare = [&](auto&& f) {
                int counted = 0;
                for (int bj = colour / 2; bj < parts; bj += 2) {
                    const int height = rows(bj + 1) - rows(bj);
                    const int j0 = rows(bj) + std::max(0, first - counted);
                    const int j1 = rows(bj) + std::min(height, last - counted);
                    counted += height;
                    if (j0 < j1) f(bj, j0, j1);
                }
            };
            forShare([&](int bj, int j0, int j1) {
                for (int j = j0; j < j1; ++j) {
                    const bool near = pinsNear(j);  // once a row, not once a block of it
                    for (int bi = colour % 2; bi < parts; bi += 2)
                        vbdBlockRow(j, columns(bi), columns(bi + 1), rows(bj), rows(bj + 1), near,
                                    blockRows_.data() + (std::size_t(j) * parts + bi) * kSums);
                }
            });
            team.sync();
            forShare([&](int bj, int j0, int j1) {
                for (int bi = colour % 2; bi < parts; bi += 2) {
                    double sum[kSums] = {};
                    for (int j = rows(bj); j < rows(bj + 1); ++j)
                        for (int e = 0; e < kSums; ++e)
                            sum[e] += blockRows_[(std::size_t(j) * parts + bi) * kSums + e];
                    const VbdLane<double> a{sum[0], sum[1], sum[2], sum[3], sum[4],
                                            sum[5], sum[6], sum[7], sum[8]};
                    double tx, ty, tz;
                    if (!(sum[kMass] > 0) || !vbdNewtonLane(a, sum[kMass], tx, ty, tz)) continue;
                    for (int j = j0; j < j1; ++j)
                        vbdShiftRow(j, columns(bi), columns(bi + 1), Vec3<T>{T(tx), T(ty), T(tz)},
                                    ownRows_.data() + std::size_t(j) * std::size_t(finest) * kOwn);
                }
            });
            team.sync();
        }
    if (!phases_.active()) return;
    for (int j = band.rowBegin; j < band.rowEnd; ++j) vbdPhasesFromGrid(j);
    team.sync();  // the sweeps read the neighbours' rows of the copy
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                                               \
    template void CpuSolver<T>::vbdLevelOwnRow(int);                                       \
    template void CpuSolver<T>::vbdBlockRow(int, int, int, int, int, bool, double*) const; \
    template void CpuSolver<T>::vbdTranslateLevels(const Band&, const Team&);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
