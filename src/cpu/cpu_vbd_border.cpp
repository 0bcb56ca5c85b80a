// vbd's border vertices on the CPU with row kernels: those within two of a side, whose springs
// leave the grid or are halved on it and whose bending has the border's weights, so that the run
// kernel (fixed offsets in phases) cannot take them. vbdSweep gathers up to 64 of one colour;
// here each is laid out lane by lane as vbdVertex would read it (addVbdStencil: the springs in
// the stencil's order with stiffnessAt and the halved damping, an absent one marked; the bending
// force from bendingForce; the contact's friction), the batch kernel (cpu_rows.h VbdBatch) takes
// the Newton steps over whole vectors, and each moved vertex ends as vbdVertex ends it (vbdMove).
// The same bits as vertex by vertex: the colour's vertices share no term, so their order is free.
#include <cstdint>

#include "cpu/cpu_solver.h"
#include "model/bending.h"
#include "model/stiffness.h"
#include "model/vbd_local.h"

namespace cloth {

namespace {

// Whole vectors of the widest instruction set: the kernel's lanes past n hold a gathered vertex.
constexpr int kBatchPad = 16;

}  // namespace

// What every lane shares: the stencil's springs, the step, the terms modelled.
template <typename T>
void CpuSolver<T>::vbdBatchTake(VbdBatch<T>& b) const {
    b.springs = int(springs_.size());
    for (std::size_t s = 0; s < springs_.size(); ++s) {
        b.restLength[s] = springs_[s].restLength;
        b.damped[s] = springs_[s].damping > 0;
    }
    b.h = dt_t_;
    b.dampingRate = dampingRate_;
    b.epsilon = dt_t_ * T(kVbdStickSpeed);
    b.bending = bending_.active();
    b.friction = vbdContacts_.active();
}

template <typename T>
void CpuSolver<T>::vbdBorderRun(VbdBatch<T>& b, const std::int64_t* vertices, int n, bool pushes) {
    const int nu = grid_.nu, nv = grid_.nv;
    const auto put = [](T(&a)[3][VbdBatch<T>::kSize], int m, const Vec3<T>& v) {
        a[0][m] = v.x, a[1][m] = v.y, a[2][m] = v.z;
    };
    const int lanes = (n + kBatchPad - 1) / kBatchPad * kBatchPad;
    for (int m = 0; m < lanes; ++m) {
        const std::int64_t k = vertices[m < n ? m : 0];
        const int i = int(k % nu), j = int(k / nu);
        const Vec3<T> p = x_.get(k), d = phases_.d.get(phases_.at(i, j));
        put(b.p, m, p);
        put(b.d, m, d);
        put(b.y, m, inertialStep_[std::size_t(k)]);
        b.inverseMass[m] = inverseMass_[std::size_t(k)];
        for (int s = 0; s < b.springs; ++s) {
            const StencilSpring<T>& spring = springs_[std::size_t(s)];
            const int qi = i + spring.di, qj = j + spring.dj;
            const bool present = qi >= 0 && qi < nu && qj >= 0 && qj < nv;
            b.present[s][m] = present;
            if (!present) {  // any finite far end: the lane drops what it gives
                put(b.q[s], m, p + Vec3<T>(spring.restLength));
                put(b.qd[s], m, d);
                b.stiffness[s][m] = b.damping[s][m] = T(0);
                continue;
            }
            put(b.q[s], m, x_.get(k + spring.indexOffset));
            if (b.damped[s]) put(b.qd[s], m, phases_.d.get(phases_.at(qi, qj)));
            b.stiffness[s][m] = stiffnessAt(spring, i, j, nu, nv);
            const bool half =
                spring.halvedOnBorder && onBorderLine(spring.di, spring.dj, i, j, nu, nv);
            b.damping[s][m] = half ? T(0.5) * spring.damping : spring.damping;
        }
        if (b.bending) {
            const auto at = [&](int a, int c) { return x_.get(std::int64_t(c) * nu + a); };
            put(b.bend, m, bendingForce<T>(bending_, i, j, at));
            b.bendDiagonal[m] = bendingDiagonal_[std::size_t(k)];
        }
        if (b.friction) {
            const std::int64_t c = vbdContactAt(k);
            put(b.slide, m, vbdContacts_.slide.get(c));
            put(b.normal, m, vbdContacts_.normal.get(c));
            b.weight[m] = vbdContacts_.weight[std::size_t(c)];
        }
    }
    kernels_->vbdBatch(b, n);
    for (int m = 0; m < n; ++m) {
        if (!b.stepped[m]) continue;
        const std::int64_t k = vertices[m];
        const Vec3<T> s(b.step[0][m], b.step[1][m], b.step[2][m]);
        const VbdLane<T> lane{b.lane[0][m], b.lane[1][m], b.lane[2][m], b.lane[3][m], b.lane[4][m],
                              b.lane[5][m], b.lane[6][m], b.lane[7][m], b.lane[8][m]};
        vbdMove(k, x_.get(k) + s, vbdDisplacement(k) + s, vbdContactAt(k), lane, pushes);
    }
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here.
template void CpuSolver<float>::vbdBatchTake(VbdBatch<float>&) const;
template void CpuSolver<double>::vbdBatchTake(VbdBatch<double>&) const;
template void CpuSolver<float>::vbdBorderRun(VbdBatch<float>&, const std::int64_t*, int, bool);
template void CpuSolver<double>::vbdBorderRun(VbdBatch<double>&, const std::int64_t*, int, bool);

}  // namespace cloth
