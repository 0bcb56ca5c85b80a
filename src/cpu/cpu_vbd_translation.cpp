// vbd's coarse correction on the rigid translation (docs/integrators.md "vbd", few sweeps): the
// mode a Gauss–Seidel sweep barely moves is the translation of every free vertex together, and
// G restricted to it is a 3 × 3 problem that needs no neighbour but the pins'. Springs and
// bending between two free vertices do not change under it, so its gradient and Hessian sum, over
// the free vertices, the terms that do: inertia and drag, friction, the springs to pinned
// vertices and the grab; each vertex that its last Newton step's projection pushed holds along
// that push with a stiff spring (10⁴ m/h²), so the translation keeps off every contact normal.
// Sums per row in double, then over the rows in order: every band takes the same step, and the
// result has the same bits for any number of threads and any instruction set.
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "model/vbd_lane.h"

namespace cloth {

namespace {

constexpr int kSums = 10;                  // gradient (3), Hessian (6), Σ m/h²
constexpr double kContactStiffness = 1e4;  // × m/h²: a contact's hold along its push

void addLane(const VbdLane<double>& a, double* out) {
    const double v[9] = {a.gx, a.gy, a.gz, a.xx, a.yy, a.zz, a.xy, a.xz, a.yz};
    for (int e = 0; e < 9; ++e) out[e] += v[e];
}

}  // namespace

template <typename T>
void CpuSolver<T>::vbdTakeParameters(const Scene& scene) {
    vbdIterations_ = scene.integrator.iterations;
    chebyshevRho_ = scene.integrator.chebyshevRho;
    translationSweeps_ = scene.integrator.translationSweeps;
    const std::size_t n = std::size_t(x_.size());
    if (chebyshevRho_ > 0 && dBefore_.empty())
        for (auto* a : {&dBefore_, &dBeforeLast_}) a->assign(n, Vec3<T>(0));
    if (translationSweeps_ > 0 && translationRows_.empty())
        translationRows_.assign(std::size_t(grid_.nv) * kSums, 0.0);
    if (translationSweeps_ > 0 && !scene.colliders.empty() && pushNormal_.size() == 0)
        pushNormal_.assign(std::int64_t(n), Vec3<T>(0));
}

// Row j's part of the translation's problem: its free vertices' inertia, drag, friction and
// contacts, the springs from its pinned vertices to free ones, and the grab if it is here.
template <typename T>
void CpuSolver<T>::vbdTranslationRow(int j, double* out) const {
    for (int e = 0; e < kSums; ++e) out[e] = 0;
    const int nu = grid_.nu, nv = grid_.nv;
    const double h = double(dt_t_), c = double(dampingRate_);
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
        const double m = 1.0 / double(inverseMass_[std::size_t(k)]);
        const double inertia = m / (h * h), drag = m * c / h;
        const std::int64_t at = phases_.active() ? phases_.at(i, j) : k;  // (vbdContactAt)
        const glm::dvec3 d(phases_.active() ? phases_.d.get(at) : displacement_.get(k));
        const glm::dvec3 y(inertialStep_[std::size_t(k)]);
        VbdLane<double> a{};
        a.gx = inertia * (d.x - y.x) + drag * d.x;
        a.gy = inertia * (d.y - y.y) + drag * d.y;
        a.gz = inertia * (d.z - y.z) + drag * d.z;
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
        addLane(a, out);
        out[9] += inertia;
    }
    if (grab_ && grab_->vertex / nu == j && !pinned_[grab_->vertex]) {
        const glm::dvec3 g = double(grab_->stiffness) *
                             (glm::dvec3(x_.get(grab_->vertex)) - glm::dvec3(grab_->target));
        VbdLane<double> a{g.x, g.y, g.z, 0, 0, 0, 0, 0, 0};
        vbdAddDiagonal(double(grab_->stiffness), a);
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
    const bool step = vbdNewtonLane(a, sum[9], tx, ty, tz);
    team.sync();  // every band has read the rows
    if (!step) return;
    const Vec3<T> t{T(tx), T(ty), T(tz)};
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        if (pinned_[k]) continue;
        Vec3<T> x = x_.get(k) + t, d = vbdDisplacement(k) + t;
        if (!colliders_.empty()) vbdProject(x, d);
        vbdSet(k, x, d);
    }
    team.sync();
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                           \
    template void CpuSolver<T>::vbdTakeParameters(const Scene&);       \
    template void CpuSolver<T>::vbdTranslationRow(int, double*) const; \
    template void CpuSolver<T>::vbdTranslate(const Band&, const Team&);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
