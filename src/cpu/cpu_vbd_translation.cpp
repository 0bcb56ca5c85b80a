// vbd's coarse correction on the rigid translation (docs/integrators.md "vbd", few sweeps): the
// mode a Gauss–Seidel sweep barely moves is the translation of every free vertex together, and
// G restricted to it is a 3 × 3 problem that needs no neighbour but the pins'. Springs and
// bending between two free vertices do not change under it, so its gradient and Hessian sum, over
// the free vertices, the terms that do: inertia and drag, friction, the springs to pinned
// vertices and the grab; each vertex that its last Newton step's projection pushed holds along
// that push with a stiff spring (10⁴ m/h²), so the translation keeps off every contact normal.
// Sums per row in double, then over the rows in order: every band takes the same step, and the
// result has the same bits for any number of threads and any instruction set.
//
// The translation's levels (cpu_vbd_levels.cpp) do the same for each block of the sheet cut into
// 2^l × 2^l equal parts, where the springs that leave the block join the pins'.
#include <algorithm>
#include <cstdint>
#include <utility>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_vbd_sums.h"
#include "model/vbd_colouring.h"
#include "model/vbd_lane.h"
#include "model/vbd_local.h"

namespace cloth {

using vbd_sums::addLane;
using vbd_sums::kContactStiffness;
using vbd_sums::kMass;
using vbd_sums::kOwn;
using vbd_sums::kSums;

template <typename T>
void CpuSolver<T>::vbdTakeParameters(const Scene& scene) {
    vbdIterations_ = scene.integrator.iterations;
    chebyshevRho_ = scene.integrator.chebyshevRho;
    translationSweeps_ = scene.integrator.translationSweeps;
    translationLevels_ =
        vbdTranslationLevels(scene.integrator.translationLevels,
                             scene.integrator.translationBlockWidth, grid_.nu, grid_.nv);
    translationLevelPasses_ = scene.integrator.translationLevelPasses;
    const std::size_t n = std::size_t(x_.size());
    if (chebyshevRho_ > 0 && dBefore_.size() == 0)
        for (auto* a : {&dBefore_, &dBeforeLast_}) a->assign(std::int64_t(n), Vec3<T>(0));
    if (translationSweeps_ > 0 && translationRows_.empty())
        translationRows_.assign(std::size_t(grid_.nv) * kSums, 0.0);
    const int parts = vbdLevelParts(translationLevels_, grid_.nu, grid_.nv);
    const std::size_t blockSums = std::size_t(grid_.nv) * std::size_t(parts) * kSums;
    if (blockRows_.size() < blockSums) blockRows_.assign(blockSums, 0.0);
    if (translationLevels_ > 0) {
        rowPinned_.assign(std::size_t(grid_.nv), 0);
        rowNonlinear_.assign(std::size_t(grid_.nv), 0);
        const std::size_t ownSums = std::size_t(grid_.nv) * std::size_t(parts) * kOwn;
        if (ownRows_.size() < ownSums) ownRows_.assign(ownSums, 0.0);
        finestColumn_.assign(std::size_t(grid_.nu) + 1, parts);
        for (int c = parts - 1; c >= 0; --c)
            for (int i = c * grid_.nu / parts; i < (c + 1) * grid_.nu / parts; ++i)
                finestColumn_[std::size_t(i)] = c;
    }
    springReach_ = 0;  // a material's: 1 (no bend springs)
    for (const StencilSpring<T>& s : springs_)
        springReach_ = std::max({springReach_, std::abs(s.di), std::abs(s.dj)});
    const bool translates = translationSweeps_ > 0 || translationLevels_ > 0;
    if (translates && !scene.colliders.empty() && pushNormal_.size() == 0)
        pushNormal_.assign(std::int64_t(n), Vec3<T>(0));
}

// Free vertex k = (i, j)'s own terms of the translation's problem: its inertia, drag, friction
// and contact hold, and the grab if it is here, added to `a`; returns its m/h².
template <typename T>
double CpuSolver<T>::vbdTranslationTerms(int i, int j, std::int64_t k, VbdLane<double>& a) const {
    const double h = double(dt_t_), c = double(dampingRate_);
    const double m = 1.0 / double(inverseMass_[std::size_t(k)]);
    const double inertia = m / (h * h), drag = m * c / h;
    const std::int64_t at = phases_.active() ? phases_.at(i, j) : k;  // (vbdContactAt)
    const glm::dvec3 d(phases_.active() ? phases_.d.get(at) : displacement_.get(k));
    const glm::dvec3 y(inertialStep_[std::size_t(k)]);
    a.gx += inertia * (d.x - y.x) + drag * d.x;
    a.gy += inertia * (d.y - y.y) + drag * d.y;
    a.gz += inertia * (d.z - y.z) + drag * d.z;
    vbdAddDiagonal(inertia + drag, a);
    // Contact terms only where there is a contact: elsewhere they add zeros.
    if (vbdContacts_.active() && vbdContacts_.weight[at] != T(0)) {
        const glm::dvec3 u = d - glm::dvec3(vbdContacts_.slide.get(at));
        const glm::dvec3 n(vbdContacts_.normal.get(at));
        vbdFrictionLane(u.x, u.y, u.z, n.x, n.y, n.z, double(vbdContacts_.weight[at]),
                        h * kVbdStickSpeed, a);
    }
    if (pushNormal_.size() > 0 && pushNormal_.get(at) != Vec3<T>(0)) {
        const glm::dvec3 n(pushNormal_.get(at));
        vbdAddOuter(kContactStiffness * inertia, n.x, n.y, n.z, a);
    }
    if (grab_ && grab_->vertex == k) {
        const glm::dvec3 g =
            double(grab_->stiffness) * (glm::dvec3(x_.get(k)) - glm::dvec3(grab_->target));
        a.gx += g.x;
        a.gy += g.y;
        a.gz += g.z;
        vbdAddDiagonal(double(grab_->stiffness), a);
    }
    return inertia;
}

// Row j's part of the translation's problem: its free vertices' own terms (vbdTranslationTerms)
// and the springs from its pinned vertices to free ones.
template <typename T>
void CpuSolver<T>::vbdTranslationRow(int j, double* out) const {
    for (int e = 0; e < kSums; ++e) out[e] = 0;
    const int nu = grid_.nu, nv = grid_.nv;
    for (int i = 0; i < nu; ++i) {
        const std::int64_t k = std::int64_t(j) * nu + i;
        if (pinned_[k]) {
            for (const StencilSpring<T>& s : springs_) {
                const int qi = i + s.di, qj = j + s.dj;
                if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
                const std::int64_t q = std::int64_t(qj) * nu + qi;
                if (pinned_[q]) continue;
                const glm::dvec3 e = glm::dvec3(x_.get(k)) - glm::dvec3(x_.get(q));
                VbdLane<double> a{};
                vbdSpringLane(e.x, e.y, e.z, double(stiffnessAt(s, i, j, nu, nv)),
                              double(s.restLength), a);
                addLane(a, out);
            }
            continue;
        }
        VbdLane<double> a{};
        out[kMass] += vbdTranslationTerms(i, j, k, a);
        addLane(a, out);
    }
}

// The translation's Newton step t = −H⁻¹g on the sums of every row, added to every free vertex's
// position and displacement, then the colliders' projection (vbdProject).
template <typename T>
void CpuSolver<T>::vbdTranslate(const Band& band, const Team& team) {
    for (int j = band.rowBegin; j < band.rowEnd; ++j)
        vbdTranslationRow(j, translationRows_.data() + std::size_t(j) * kSums);
    team.sync();
    double sum[kSums] = {};
    for (int j = 0; j < grid_.nv; ++j)
        for (int e = 0; e < kSums; ++e) sum[e] += translationRows_[std::size_t(j) * kSums + e];
    const VbdLane<double> a{sum[0], sum[1], sum[2], sum[3], sum[4], sum[5], sum[6], sum[7], sum[8]};
    double tx, ty, tz;
    const bool step = vbdNewtonLane(a, sum[kMass], tx, ty, tz);
    team.sync();  // every band has read the rows
    if (!step) return;
    for (int j = band.rowBegin; j < band.rowEnd; ++j)
        vbdShiftRow(j, 0, grid_.nu, Vec3<T>{T(tx), T(ty), T(tz)});
    team.sync();
}

// Row j's free vertices in columns [i0, i1) moved by t, position and displacement, then the
// colliders' projection (by runs through their row code with row kernels, where their cull lets
// one touch the run: the same bits as projecting every vertex). own: row j's own sums of the
// levels (vbdLevelOwnRow), kept up to date with the moves; null for the translation's step.
// The levels leave the copy's positions in phases to vbdPhasesFromGrid after their pass: at
// 1024² they are 12 MB, streamed once a level otherwise.
namespace {

// a_k += t for the n entries from k0 whose pinned[k] is 0, as a choice in every lane (vectorised).
template <typename T>
void shiftFree(Soa3<T>& a, const std::uint8_t* pinned, std::int64_t k0, int n, const Vec3<T>& t) {
    T* __restrict x = a.x.data() + k0, * __restrict y = a.y.data() + k0;
    T* __restrict z = a.z.data() + k0;
    const std::uint8_t* __restrict pin = pinned + k0;
    for (int m = 0; m < n; ++m) {
        const bool free = pin[m] == 0;
        x[m] = free ? x[m] + t.x : x[m];
        y[m] = free ? y[m] + t.y : y[m];
        z[m] = free ? z[m] + t.z : z[m];
    }
}

}  // namespace

template <typename T>
void CpuSolver<T>::vbdShiftRow(int j, int i0, int i1, const Vec3<T>& t, double* own) {
    const std::int64_t row = std::int64_t(j) * grid_.nu;
    const bool phased = phases_.active();
    const bool phasesLater = phased && own;  // the levels' (see above)
    shiftFree(x_, pinned_.data(), row + i0, i1 - i0, t);
    if (!phased) shiftFree(displacement_, pinned_.data(), row + i0, i1 - i0, t);
    // In phases each residue of i mod 5 is a contiguous run: the copy x there is x_'s, bit for
    // bit, so it moves by the same sum (the levels' copy takes x_ after their pass instead).
    for (int r = 0; r < kVbdColours && phased; ++r) {
        const int first = i0 + ((r - i0) % kVbdColours + kVbdColours) % kVbdColours;
        if (first >= i1) continue;
        const std::int64_t at = phases_.at(first, j);
        const int n = (i1 - 1 - first) / kVbdColours + 1;
        if (!phasesLater) shiftFree(phases_.x, phases_.pinned.data(), at, n, t);
        shiftFree(phases_.d, phases_.pinned.data(), at, n, t);
    }
    // The linear vertices' gradient Σ m/h² (d − ŷ) + m c/h d moves by their Σ (m/h² + m c/h)
    // times the shift, and by each one's weight times its push.
    if (own)
        for (int c = finestColumn_[std::size_t(i0)]; c < finestColumn_[std::size_t(i1)]; ++c)
            for (int e = 0; e < 3; ++e) own[c * kOwn + e] += double(t[e]) * own[c * kOwn + kSums];
    const auto pushed = [&](int i, std::int64_t k, const Vec3<T>& push) {
        if (!own || !vbdLinearOwn(k, phased ? phases_.at(i, j) : k)) return;
        double* o = own + finestColumn_[std::size_t(i)] * kOwn;
        const double w = vbdInertiaDrag(k);
        for (int e = 0; e < 3; ++e) o[e] += w * double(push[e]);
    };
    if (colliders_.empty()) return;
    if (!phased) {  // (no row kernels)
        if (!colliders_.mayTouchRow(x_.row(row + i0), i1 - i0)) return;
        for (int i = i0; i < i1; ++i) {
            const std::int64_t k = row + i;
            if (pinned_[k]) continue;
            Vec3<T> x = x_.get(k), d = displacement_.get(k);
            const Vec3<T> before = x;
            vbdProject(x, d);
            vbdSet(k, x, d);
            pushed(i, k, x - before);
        }
        return;
    }
    constexpr int kRun = 64;
    alignas(64) T p[3][kRun], v[3][kRun];  // v: not read or written with `touched`
    std::int32_t touched[kRun] = {};       // asks applyRow for the positions alone (unread)
    for (int c = i0; c < i1; c += kRun) {
        const int n = std::min(kRun, i1 - c);
        const ConstRow3<T> x = std::as_const(x_).row(row + c);
        for (int m = 0; m < n; ++m) p[0][m] = x.x[m], p[1][m] = x.y[m], p[2][m] = x.z[m];
        if (!colliders_.applyRow({p[0], p[1], p[2]}, {v[0], v[1], v[2]}, n, *kernels_, touched))
            continue;
        for (int m = 0; m < n; ++m) {
            const std::int64_t k = row + c + m;
            const Vec3<T> moved(p[0][m], p[1][m], p[2][m]), old = x_.get(k);
            if (pinned_[k] || moved == old) continue;
            const std::int64_t at = phases_.at(c + m, j);
            x_.set(k, moved);
            if (!phasesLater) phases_.x.set(at, moved);
            phases_.d.set(at, phases_.d.get(at) + (moved - old));
            pushed(c + m, k, moved - old);
        }
    }
}

// Row j's positions in phases from x_: each phase's run takes every fifth of the row.
template <typename T>
void CpuSolver<T>::vbdPhasesFromGrid(int j) {
    const std::int64_t row = std::int64_t(j) * grid_.nu;
    for (int r = 0; r < kVbdColours && r < grid_.nu; ++r) {
        const ConstRow3<T> from = std::as_const(x_).row(row + r);
        const Row3<T> to = phases_.x.row(phases_.at(r, j));
        const T* __restrict gx = from.x, * __restrict gy = from.y, * __restrict gz = from.z;
        T* __restrict px = to.x, * __restrict py = to.y, * __restrict pz = to.z;
        const int n = (grid_.nu - 1 - r) / kVbdColours + 1;
        for (int m = 0; m < n; ++m) {
            const std::int64_t q = std::int64_t(kVbdColours) * m;
            px[m] = gx[q], py[m] = gy[q], pz[m] = gz[q];
        }
    }
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                                                    \
    template void CpuSolver<T>::vbdPhasesFromGrid(int);                                         \
    template void CpuSolver<T>::vbdTakeParameters(const Scene&);                                \
    template void CpuSolver<T>::vbdTranslationRow(int, double*) const;                          \
    template void CpuSolver<T>::vbdTranslate(const Band&, const Team&);                         \
    template void CpuSolver<T>::vbdShiftRow(int, int, int, const Vec3<T>&, double*);            \
    template double CpuSolver<T>::vbdTranslationTerms(int, int, std::int64_t, VbdLane<double>&) \
        const;
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
