// vbd on the CPU (docs/integrators.md "vbd"): Vertex Block Descent (Chen, Macklin et al. 2024)
// minimises backward Euler's incremental potential by Gauss–Seidel sweeps of 3×3 Newton steps,
// one vertex at a time (model/vbd_local.h), on the iterate (x, d): positions and the step's
// displacements d = x − x_n, moved alike. The colours of model/vbd_colouring.h run one after
// another; within a colour every band steps its own vertices, which share no energy term with
// each other, so the result has the same bits for any number of threads.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"
#include "model/forces.h"
#include "model/start_inside.h"
#include "model/vbd_colouring.h"
#include "model/vbd_local.h"

namespace cloth {

// One step: the start (ŷ, the initial guess), `iterations` sweeps over the five colours (the
// translation's levels before the first and, with more passes, before sweeps spread over the
// rest; the first translation_sweeps followed by the translation's step; each with ρ > 0 by the
// Chebyshev extrapolation), then v_{n+1} = d/h and finishStep's pins, colliders and check (by
// rows with row kernels, cpu_vbd_finish.cpp); a vertex that started inside a collider keeps none
// of the correction that put it out as velocity (model/start_inside.h).
template <typename T>
bool CpuSolver<T>::stepVbd(Band& band, const Team& team, long stepNumber) {
    vbdStart(band, team, stepNumber);
    const int passes = translationLevels_ > 0 ? translationLevelPasses_ : 0;
    const auto levelsBefore = [&](int n) { return vbdLevelsBefore(n, vbdIterations_, passes); };
    const int chebyshevStart = vbdChebyshevStart(translationSweeps_, vbdIterations_, passes);
    double omega = 1;
    for (int n = 1; n <= vbdIterations_; ++n) {
        if (levelsBefore(n)) vbdTranslateLevels(band, team);  // (cpu_vbd_levels.cpp)
        // The pushes the translation's steps read: those of the sweeps each follows and of the
        // last sweep (read by the next step's levels and translation); the others' are not.
        const bool pushes = n <= translationSweeps_ || n == vbdIterations_ || levelsBefore(n + 1);
        for (int colour = 0; colour < kVbdColours; ++colour) {
            vbdSweep(band, colour, pushes);
            team.sync();  // the next colour reads this one's new positions
        }
        if (n <= translationSweeps_) vbdTranslate(band, team);  // (cpu_vbd_translation.cpp)
        if (chebyshevRho_ > 0) {
            omega = vbdChebyshevOmega(n, chebyshevStart, chebyshevRho_, omega);
            vbdAccelerate(band, omega);
            team.sync();
        }
    }
    if (kernels_) return vbdFinishRows(band);
    const T h = dt_t_;
    const auto collide = [this](Vec3<T>& p, Vec3<T>& w) { colliders_.apply(p, w); };
    const auto surface = [this](const Vec3<T>& p) { return colliders_.surfaceVelocity(p); };
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> x = x_.get(k), d = vbdDisplacement(k), v = d / h;
        const bool collides = !colliders_.empty() && !pinned_[k];  // (model/start_inside.h)
        if (!finishStep(band, k, x,
                        collides ? withoutStartCorrection(x - d, v, h, collide, surface) : v))
            return false;
    }
    return true;
}

// The inertial target's displacement ŷ = h v_n + h² (g + F_w(x_n)/m), the wind taken at x_n
// from the normals every band still holds; then, once every band has read them, the initial
// guess (vbdInitialGuess: x = x_n + d); pinned vertices at their pin, d = pin − x_n.
template <typename T>
void CpuSolver<T>::vbdStart(const Band& band, const Team& team, long stepNumber) {
    const int nu = grid_.nu, nv = grid_.nv;
    const T h = dt_t_;
    auto at = [&](int i, int j) { return x_.get(std::int64_t(j) * nu + i); };
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        Vec3<T> a = gravity_;
        if (features_.wind) {
            const int i = int(k % nu), j = int(k / nu);
            const Vec3<T> n = vertexNormal<T>(nu, nv, i, j, at);
            a += inverseMass_[std::size_t(k)] * windForce(n, windDirection_, windStrengthAt(i, j));
        }
        inertialStep_[k] = h * v_.get(k) + (h * h) * a;
    }
    team.sync();
    const bool history = stepNumber >= vbdHistoryFrom_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> v = v_.get(k), start = x_.get(k);
        const Vec3<T> d = pinned_[k] ? pinPosition_[k] - start
                                     : vbdInitialGuess(v, vPrevious_[k], gravity_, h, history);
        vPrevious_[k] = v;
        x_.set(k, pinned_[k] ? pinPosition_[k] : start + d);
        displacement_.set(k, d);
        if (dBefore_.size() > 0 && !phases_.active()) dBefore_.set(k, d);
    }
    if (phases_.active()) vbdFillPhases(band);
    team.sync();
}

// The row kernel's copy of this band's rows, refreshed whole (pins and masses can change): each
// phase of a row written contiguously from every fifth vertex.
template <typename T>
void CpuSolver<T>::vbdFillPhases(const Band& band) {
    const int nu = grid_.nu;
    const bool bending = bending_.active();
    for (int j = band.rowBegin; j < band.rowEnd; ++j)
        for (int p = 0; p < kVbdColours && p < nu; ++p) {
            const std::int64_t k0 = std::int64_t(j) * nu + p, a0 = phases_.at(p, j);
            const int count = (nu - p + kVbdColours - 1) / kVbdColours;
            const Vec3<T>* __restrict y = inertialStep_.data() + k0;
            const T* __restrict inverseMass = inverseMass_.data() + k0;
            const std::uint8_t* __restrict pinned = pinned_.data() + k0;
            for (int m = 0; m < count; ++m) {
                const std::int64_t k = kVbdColours * std::int64_t(m), a = a0 + m;
                phases_.x.x[a] = x_.x[k0 + k], phases_.x.y[a] = x_.y[k0 + k];
                phases_.x.z[a] = x_.z[k0 + k];
                phases_.d.x[a] = displacement_.x[k0 + k], phases_.d.y[a] = displacement_.y[k0 + k];
                phases_.d.z[a] = displacement_.z[k0 + k];
                phases_.y.x[a] = y[k].x, phases_.y.y[a] = y[k].y, phases_.y.z[a] = y[k].z;
                phases_.inverseMass[a] = inverseMass[k];
                phases_.pinned[a] = pinned[k];
            }
            if (bending)
                for (int m = 0; m < count; ++m)
                    phases_.bendDiagonal[a0 + m] = bendingDiagonal_[k0 + kVbdColours * m];
            if (dBefore_.size() > 0) {  // Chebyshev's iterate before the first sweep
                const Row3<T> from = phases_.d.row(a0), to = dBefore_.row(a0);
                std::copy_n(from.x, count, to.x);
                std::copy_n(from.y, count, to.y);
                std::copy_n(from.z, count, to.z);
            }
        }
}

// The Newton steps of one colour's vertices in this band's rows: in row j the colour's columns
// are i ≡ colour − 2j (mod 5). With row kernels, the run of them two or more from every border
// goes through the vbd kernel (cpu/cpu_rows.h), up to kRun at a time, the rest through the batch
// kernel once 64 are gathered (and at the end), and the grabbed vertex vertex by vertex. The
// colour's vertices share no term, so the order is free.
template <typename T>
void CpuSolver<T>::vbdSweep(const Band& band, int colour, bool pushes) {
    const int nu = grid_.nu, nv = grid_.nv;
    VbdBatch<T> batch;  // the border's vertices, through the batch kernel (cpu_vbd_border.cpp)
    std::int64_t border[VbdBatch<T>::kSize];
    int borderCount = 0;
    if (kernels_) vbdBatchTake(batch);
    auto step = [&](int i, int j) {
        const std::int64_t k = std::int64_t(j) * nu + i;
        if (pinned_[k]) return;
        if (!kernels_ || (grab_ && grab_->vertex == k)) {
            vbdVertex(k, i, j, pushes);
            return;
        }
        border[borderCount++] = k;
        if (borderCount == VbdBatch<T>::kSize) {
            vbdBorderRun(batch, border, borderCount, pushes);
            borderCount = 0;
        }
    };
    VbdRow<T> row{};
    if (kernels_) row = vbdRow();
    constexpr int kRun = 64;
    std::uint8_t moved[kRun];
    alignas(64) T hessian[6][kRun];
    row.moved = moved;
    if (row.contactWeight)
        for (int e = 0; e < 6; ++e) row.hessian[e] = hessian[e];
    for (int j = band.rowBegin; j < band.rowEnd; ++j) {
        int i = ((colour - 2 * j) % kVbdColours + kVbdColours) % kVbdColours;
        // Whole vectors read past the runs of rows j − 2 … j + 2 into the next row's first
        // phase: only where those rows are this band's (or there is no other band), as another
        // thread writes its own rows' vertices of this colour meanwhile.
        row.wholeVectors = bands_.size() == 1 || (j - 2 >= band.rowBegin && j + 3 < band.rowEnd);
        if (kernels_ && j >= 2 && j < nv - 2) {
            for (; i < 2; i += kVbdColours) step(i, j);
            for (; i <= nu - 3;) {
                const int n = std::min(kRun, (nu - 3 - i) / kVbdColours + 1);
                row.first = std::int64_t(j) * nu + i;
                row.at = phases_.at(i, j);
                vbdRunOffsets(row, i);
                kernels_->vbd(row, n);
                if (row.skip >= row.first && row.skip < row.first + kVbdColours * n &&
                    (row.skip - row.first) % kVbdColours == 0 && !pinned_[row.skip])
                    vbdVertex(row.skip, int(row.skip % nu), j, pushes);
                if (!colliders_.empty())
                    vbdCollideRun(row.first, row.at, moved, n, row.hessian, pushes);
                i += kVbdColours * n;
            }
        }
        for (; i < nu; i += kVbdColours) step(i, j);
    }
    if (borderCount > 0) vbdBorderRun(batch, border, borderCount, pushes);
}

// What the vbd kernel reads of the solver, for any run: the arrays, the stencil's springs inside
// the sheet (no border halving there) and bending's interior weights.
template <typename T>
VbdRow<T> CpuSolver<T>::vbdRow() {
    VbdRow<T> r{};
    r.x = x_.row(0);
    r.px = phases_.x.row(0);
    r.pd = phases_.d.row(0);
    r.py = phases_.y.row(0);
    r.inverseMass = phases_.inverseMass.data();
    r.bendDiagonal = phases_.bendDiagonal.data();
    r.pinned = phases_.pinned.data();
    r.skip = grab_ ? grab_->vertex : -1;
    r.springs = int(springs_.size());
    for (std::size_t s = 0; s < springs_.size(); ++s) {
        r.stiffness[s] = springs_[s].stiffness;
        r.restLength[s] = springs_[s].restLength;
        r.damping[s] = springs_[s].damping;
    }
    r.h = dt_t_;
    r.dampingRate = dampingRate_;
    if (vbdContacts_.active()) {
        r.contactNormal = vbdContacts_.normal.row(0);
        r.contactSlide = vbdContacts_.slide.row(0);
        r.contactWeight = vbdContacts_.weight.data();
        r.epsilon = dt_t_ * T(kVbdStickSpeed);
    }
    r.bending = bending_.active();
    r.wu = T(bending_.alongU);
    r.wv = T(bending_.alongV);
    r.t = T(bending_.twist);
    return r;
}

// The offsets in phases of a run from column i (they depend on i mod 5): the springs' far ends
// and bendingLane's stencil (row j's columns −2 … 2, rows j ∓ 1's −1 … 1, rows j ∓ 2).
template <typename T>
void CpuSolver<T>::vbdRunOffsets(VbdRow<T>& r, int i) const {
    for (std::size_t s = 0; s < springs_.size(); ++s)
        r.offset[s] = phases_.offset(i, springs_[s].di, springs_[s].dj);
    static constexpr int kBend[13][2] = {{-2, 0},  {-1, 0}, {0, 0},  {1, 0},  {2, 0},
                                         {-1, -1}, {0, -1}, {1, -1}, {-1, 1}, {0, 1},
                                         {1, 1},   {0, -2}, {0, 2}};
    for (int e = 0; e < 13; ++e) r.bendAt[e] = phases_.offset(i, kBend[e][0], kBend[e][1]);
}

template <typename T>
void CpuSolver<T>::vbdSet(std::int64_t k, const Vec3<T>& x, const Vec3<T>& d) {
    x_.set(k, x);
    if (!phases_.active()) {
        displacement_.set(k, d);
        return;
    }
    const std::int64_t a = phases_.at(k);
    phases_.x.set(a, x);
    phases_.d.set(a, d);
}

// One vertex's Newton step on its local G (with its contact's friction), then the colliders'
// projection of the new position (docs/integrators.md "vbd": contact and friction); the
// displacement moves with the position.
template <typename T>
void CpuSolver<T>::vbdVertex(std::int64_t k, int i, int j, bool pushes) {
    const T h = dt_t_, mass = T(1) / inverseMass_[std::size_t(k)];
    Vec3<T> x = x_.get(k), d = vbdDisplacement(k);
    VbdLocal<T> local;
    addVbdInertia(d, inertialStep_[k], mass, h, dampingRate_, local);
    const T bendDiagonal = bending_.active() ? bendingDiagonal_[std::size_t(k)] : T(0);
    if (phases_.active())
        addVbdStencil(grid_.nu, grid_.nv, springs_, bending_, bendDiagonal, x_,
                      PhasedDisplacements<T>{phases_}, h, k, i, j, local);
    else
        addVbdStencil(grid_.nu, grid_.nv, springs_, bending_, bendDiagonal, x_, displacement_, h, k,
                      i, j, local);
    if (grab_ && grab_->vertex == k) addVbdGrab(x, grab_->target, grab_->stiffness, local);
    const std::int64_t c = vbdContactAt(k);
    if (vbdContacts_.active())
        addVbdFriction(d - vbdContacts_.slide.get(c), vbdContacts_.normal.get(c),
                       vbdContacts_.weight[c], h * T(kVbdStickSpeed), local);
    Vec3<T> s;
    if (vbdNewtonStep(local, double(mass) / (double(h) * h), s))
        vbdMove(k, x + s, d + s, c, vbdLane(local), pushes);
}

// Vertex k's iterate after its Newton step (position x, displacement d): the colliders'
// projection, with the contact c's friction set from the local problem `lane`, then stored.
template <typename T>
void CpuSolver<T>::vbdMove(std::int64_t k, Vec3<T> x, Vec3<T> d, std::int64_t c,
                           const VbdLane<T>& lane, bool pushes) {
    if (!colliders_.empty()) {
        Vec3<T> p = x;
        const auto surface = colliders_.project(p);
        if (vbdContacts_.active()) vbdTouch(c, x, p, surface, lane);
        if (pushes && pushNormal_.size() > 0) vbdPushed(c, x, p);
        d += p - x;
        x = p;
    }
    vbdSet(k, x, d);
}

// Contact c after a projection moved the Newton step's x to p against `surface` (the last that
// touched it), H the local problem's Hessian there: its normal n = (p − x)/|p − x|, the normal
// force λ = |p − x| nᵀHn (vbdNormalStiffness), the surface's c_f and h v_c; no contact where
// nothing pushed.
template <typename T>
void CpuSolver<T>::vbdTouch(std::int64_t c, const Vec3<T>& x, const Vec3<T>& p,
                            const typename CpuColliders<T>::Surface& surface,
                            const VbdLane<T>& hessian) {
    const Vec3<T> push = p - x;
    const T pushed = glm::length(push);
    if (!(pushed > T(0))) {
        vbdContacts_.weight[c] = T(0);
        return;
    }
    const Vec3<T> n = push / pushed;
    vbdContacts_.normal.set(c, n);
    vbdContacts_.slide.set(c, dt_t_ * surface.velocity);
    vbdContacts_.weight[c] =
        surface.friction * (pushed * vbdNormalStiffness(hessian, n.x, n.y, n.z));
}

// vbdTouch on the run's vertices that moved (k = first + 5m, in phases at + m, moved[m]): the
// colliders through their row code (CpuColliders::applyRow: the same bits as apply, vertex by
// vertex) on the whole run, read contiguously from the copy in phases; the vertices that did not
// move keep their position. hessian: the run's local Hessians as the kernel exported them, or
// null for a projection that sets no contact (Chebyshev's extrapolation).
template <typename T>
void CpuSolver<T>::vbdCollideRun(std::int64_t first, std::int64_t at, const std::uint8_t* moved,
                                 int n, const T* const* hessian, bool pushes) {
    constexpr int kRun = 64;
    alignas(64) T p[3][kRun], v[3][kRun];  // v: not read or written with `touched`
    std::int32_t touched[kRun] = {};       // which collider touched each vertex last (surfaceOf)
    const T* position[3] = {phases_.x.x.data() + at, phases_.x.y.data() + at,
                            phases_.x.z.data() + at};
    for (int c = 0; c < 3; ++c)
        for (int m = 0; m < n; ++m) p[c][m] = position[c][m];
    if (!colliders_.applyRow({p[0], p[1], p[2]}, {v[0], v[1], v[2]}, n, *kernels_, touched)) {
        // Nothing pushed: no contact and no push where there was one (vbdTouch, vbdPushed).
        for (int m = 0; m < n; ++m) {
            if (!moved[m]) continue;
            if (hessian && hessian[0]) vbdContacts_.weight[at + m] = T(0);
            if (pushes && pushNormal_.size() > 0) pushNormal_.set(at + m, Vec3<T>(0));
        }
        return;
    }
    // Which vertices have anything to do, over whole vectors: pushed, or a contact to update
    // (one to lift off included), or a push to keep.
    const bool contacts = hessian && hessian[0], keepPushes = pushes && pushNormal_.size() > 0;
    std::uint8_t work[kRun];
    for (int m = 0; m < n; ++m)
        work[m] =
            std::uint8_t(unsigned(p[0][m] != position[0][m]) | unsigned(p[1][m] != position[1][m]) |
                         unsigned(p[2][m] != position[2][m]) | unsigned(keepPushes));
    if (contacts) {
        const T* weight = vbdContacts_.weight.data() + at;
        for (int m = 0; m < n; ++m) work[m] |= std::uint8_t(weight[m] != T(0));
    }
    for (int m = 0; m < n; ++m) {
        if (!moved[m] || !work[m]) continue;
        const Vec3<T> pushed(p[0][m], p[1][m], p[2][m]), old = phases_.x.get(at + m);
        // The run's projection ran on whole rows and marked which collider touched each last.
        if (contacts && (pushed != old || vbdContacts_.weight[at + m] != T(0)))
            vbdTouch(at + m, old, pushed,
                     pushed != old ? colliders_.surfaceOf(touched[m], old)
                                   : typename CpuColliders<T>::Surface{},
                     {0, 0, 0, hessian[0][m], hessian[1][m], hessian[2][m], hessian[3][m],
                      hessian[4][m], hessian[5][m]});
        if (pushes && pushNormal_.size() > 0) vbdPushed(at + m, old, pushed);
        if (pushed == old) continue;
        const std::int64_t k = first + std::int64_t(kVbdColours) * m;
        const Vec3<T> d = phases_.d.get(at + m) + (pushed - old);
        x_.set(k, pushed);
        phases_.x.set(at + m, pushed);
        phases_.d.set(at + m, d);
    }
}

// The colliders' projection alone on an extrapolated iterate (Chebyshev's): no friction, no
// change to the contacts; the displacement moves with the position.
template <typename T>
void CpuSolver<T>::vbdProject(Vec3<T>& x, Vec3<T>& d) const {
    Vec3<T> p = x;
    colliders_.project(p);
    d += p - x;
    x = p;
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                                                   \
    template bool CpuSolver<T>::stepVbd(Band&, const Team&, long);                             \
    template void CpuSolver<T>::vbdStart(const Band&, const Team&, long);                      \
    template void CpuSolver<T>::vbdSweep(const Band&, int, bool);                              \
    template VbdRow<T> CpuSolver<T>::vbdRow();                                                 \
    template void CpuSolver<T>::vbdRunOffsets(VbdRow<T>&, int) const;                          \
    template void CpuSolver<T>::vbdSet(std::int64_t, const Vec3<T>&, const Vec3<T>&);          \
    template void CpuSolver<T>::vbdFillPhases(const Band&);                                    \
    template void CpuSolver<T>::vbdVertex(std::int64_t, int, int, bool);                       \
    template void CpuSolver<T>::vbdMove(std::int64_t, Vec3<T>, Vec3<T>, std::int64_t,          \
                                        const VbdLane<T>&, bool);                              \
    template void CpuSolver<T>::vbdTouch(std::int64_t, const Vec3<T>&, const Vec3<T>&,         \
                                         const typename CpuColliders<T>::Surface&,             \
                                         const VbdLane<T>&);                                   \
    template void CpuSolver<T>::vbdCollideRun(std::int64_t, std::int64_t, const std::uint8_t*, \
                                              int, const T* const*, bool);                     \
    template void CpuSolver<T>::vbdProject(Vec3<T>&, Vec3<T>&) const;
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
