// vbd on the CPU (docs/integrators.md "vbd"): Vertex Block Descent (Chen, Macklin et al. 2024)
// minimises backward Euler's incremental potential by Gauss–Seidel sweeps of 3×3 Newton steps,
// one vertex at a time (model/vbd_local.h). The colours of model/vbd_colouring.h run one after
// another; within a colour every band steps its own vertices, which share no energy term with
// each other, so the result has the same bits for any number of threads.
#include <cstddef>
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "cpu/cpu_solver_vertex.h"
#include "model/forces.h"
#include "model/vbd_colouring.h"
#include "model/vbd_local.h"

namespace cloth {

// One step: the start (x_n, y, the initial guess), `iterations` sweeps over the five colours
// (each followed, with ρ > 0, by the Chebyshev extrapolation), then v_{n+1} = (x − x_n)/h and
// finishStep's pins, colliders and check.
template <typename T>
bool CpuSolver<T>::stepVbd(Band& band, const Team& team, long stepNumber) {
    vbdStart(band, team, stepNumber);
    double omega = 1;
    for (int n = 1; n <= vbdIterations_; ++n) {
        for (int colour = 0; colour < kVbdColours; ++colour) {
            vbdSweep(band, colour);
            team.sync();  // the next colour reads this one's new positions
        }
        if (chebyshevRho_ > 0) {
            omega = chebyshevOmega(n, chebyshevRho_, omega);
            vbdAccelerate(band, omega);
            team.sync();
        }
    }
    const T h = dt_t_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> x = x_.get(k);
        if (!finishStep(band, k, x, (x - xStart_.get(k)) / h)) return false;
    }
    return true;
}

// x_n and the inertial target y = x_n + h v_n + h² (g + F_w(x_n)/m): the wind is taken
// explicitly at x_n, from the normals of the positions every band still holds. Then, once every
// band has read them, the initial guess (vbdInitialGuess); pinned vertices at their pin.
template <typename T>
void CpuSolver<T>::vbdStart(const Band& band, const Team& team, long stepNumber) {
    const int nu = grid_.nu, nv = grid_.nv;
    const T h = dt_t_;
    auto at = [&](int i, int j) { return x_.get(std::int64_t(j) * nu + i); };
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> x = x_.get(k);
        Vec3<T> a = gravity_;
        if (features_.wind) {
            const int i = int(k % nu), j = int(k / nu);
            const Vec3<T> n = vertexNormal<T>(nu, nv, i, j, at);
            a += inverseMass_[std::size_t(k)] * windForce(n, windDirection_, windStrengthAt(i, j));
        }
        xStart_.set(k, x);
        inertial_[k] = x + h * v_.get(k) + (h * h) * a;
    }
    team.sync();
    const bool history = stepNumber >= vbdHistoryFrom_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        const Vec3<T> v = v_.get(k);
        const Vec3<T> x =
            pinned_[k] ? pinPosition_[k]
                       : vbdInitialGuess(xStart_.get(k), v, vPrevious_[k], gravity_, h, history);
        vPrevious_[k] = v;
        x_.set(k, x);
        if (!xBefore_.empty()) xBefore_[k] = x;
    }
    team.sync();
}

// The Newton steps of one colour's vertices in this band's rows: in row j the colour's columns
// are i ≡ colour − 2j (mod 5).
template <typename T>
void CpuSolver<T>::vbdSweep(const Band& band, int colour) {
    const int nu = grid_.nu;
    for (int j = band.rowBegin; j < band.rowEnd; ++j) {
        const int first = ((colour - 2 * j) % kVbdColours + kVbdColours) % kVbdColours;
        for (int i = first; i < nu; i += kVbdColours) {
            const std::int64_t k = std::int64_t(j) * nu + i;
            if (!pinned_[k]) vbdVertex(k, i, j);
        }
    }
}

// One vertex's Newton step on its local G, then the colliders' projection of the new position
// (docs/integrators.md "vbd": contact by projection after each local step).
template <typename T>
void CpuSolver<T>::vbdVertex(std::int64_t k, int i, int j) {
    const T h = dt_t_, mass = T(1) / inverseMass_[std::size_t(k)];
    Vec3<T> x = x_.get(k);
    VbdLocal<T> local;
    addVbdInertia(x, inertial_[k], xStart_.get(k), mass, h, dampingRate_, local);
    const T bendDiagonal = bending_.active() ? bendingDiagonal_[std::size_t(k)] : T(0);
    addVbdStencil(grid_.nu, grid_.nv, springs_, bending_, bendDiagonal, x_, xStart_, h, k, i, j,
                  local);
    if (grab_ && grab_->vertex == k) addVbdGrab(x, grab_->target, grab_->stiffness, local);
    if (!vbdNewtonStep(local, double(mass) / (double(h) * h), x)) return;
    vbdCollide(k, x);
    x_.set(k, x);
}

// The colliders on an iterate (docs/integrators.md "vbd", contact): the position is projected
// out as at a step's end, and the friction of docs/colliders.md §2 — which takes from the
// tangential velocity at most c_f times the normal velocity removed — takes the same from the
// step's displacement x − x_n = h v. The projection alone would leave no normal velocity for
// finishStep's friction to act on: a resting vertex would slide freely.
template <typename T>
void CpuSolver<T>::vbdCollide(std::int64_t k, Vec3<T>& x) const {
    if (colliders_.empty()) return;
    const T h = dt_t_;
    const Vec3<T> before = (x - xStart_.get(k)) / h;
    Vec3<T> p = x, v = before;
    applyColliders(p, v);
    const Vec3<T> push = p - x;
    const T pushed = glm::length(push);
    if (!(pushed > T(0))) return;
    const Vec3<T> n = push / pushed, lost = before - v;
    x = p - h * (lost - glm::dot(lost, n) * n);  // the tangential part friction took
}

// Chebyshev acceleration after sweep n (VBD §3.8): x_n ← ω_n (x̄_n − x_{n−2}) + x_{n−2} for the
// free vertices, then the colliders' projection again.
template <typename T>
void CpuSolver<T>::vbdAccelerate(const Band& band, double omega) {
    const T w = T(omega);
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        if (pinned_[k]) continue;
        Vec3<T> x = x_.get(k);
        if (omega > 1) {
            x = w * (x - xBeforeLast_[k]) + xBeforeLast_[k];
            vbdCollide(k, x);
            x_.set(k, x);
        }
        xBeforeLast_[k] = xBefore_[k];
        xBefore_[k] = x;
    }
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
#define CLOTH_INSTANTIATE(T)                                              \
    template bool CpuSolver<T>::stepVbd(Band&, const Team&, long);        \
    template void CpuSolver<T>::vbdStart(const Band&, const Team&, long); \
    template void CpuSolver<T>::vbdSweep(const Band&, int);               \
    template void CpuSolver<T>::vbdVertex(std::int64_t, int, int);        \
    template void CpuSolver<T>::vbdCollide(std::int64_t, Vec3<T>&) const; \
    template void CpuSolver<T>::vbdAccelerate(const Band&, double);
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
