// What the vbd row kernel (cpu/cpu_rows.h VbdRow) reads, in the order it reads it. A colour's
// vertices in a row are five apart (model/vbd_colouring.h); in the grid's own order a vector of
// them is built one scalar at a time. Here every row is split into its five phases, columns
// i ≡ p (mod 5) one after another:
//
//     (i, j) → j · nu + start[i mod 5] + ⌊i/5⌋
//
// so a run of one colour's vertices, and the same run shifted by any stencil offset (di, dj), is
// contiguous. Phase p of a row starts at start[p] (the phases before it hold ⌈(nu − q)/5⌉ columns
// each): no padding between rows, nu · nv entries, then kVbdSlack more (cpu_rows.h: the row
// kernel's last vector of a run reads past the run; those lanes are computed and never stored),
// pinned there and zero elsewhere. The solver keeps this copy of the positions beside its own
// (both written on every move, cpu_vbd.cpp vbdSet), the displacements only here during the
// sweeps, and fills the rest once a step (vbdStart).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "cpu/cpu_soa.h"
#include "model/scene.h"

namespace cloth {

template <typename T>
struct VbdPhases {
    int nu = 0, nv = 0;
    std::int64_t start[5]{};
    // The iterate (positions x, displacements d = x − x_n), the inertial target's ŷ = y − x_n.
    Soa3<T> x, d, y;
    AlignedVector<T> inverseMass;
    AlignedVector<T> bendDiagonal;  // with bending only (sized by the solver)
    AlignedVector<std::uint8_t> pinned;

    void configure(int u, int v) {
        nu = u;
        nv = v;
        for (int p = 1; p < 5; ++p) start[p] = start[p - 1] + (u - (p - 1) + 4) / 5;
        const std::int64_t n = std::int64_t(u) * v + kVbdSlack;
        for (Soa3<T>* a : {&x, &d, &y}) a->assign(n, Vec3<T>(0));
        inverseMass.assign(std::size_t(n), T(0));
        pinned.assign(std::size_t(n), 1);
    }
    // Bending's diagonal weights for `vertices` vertices (0: no bending).
    void sizeBendDiagonal(std::size_t vertices) {
        bendDiagonal.assign(vertices > 0 ? vertices + std::size_t(kVbdSlack) : 0, T(0));
    }
    bool active() const { return nu > 0; }
    // What the copy holds for the grid's vertices (the slack, a constant, is not counted: the
    // memory model, cpu/cpu_memory.h, is per vertex).
    std::size_t bytes() const {
        if (!active()) return 0;
        const std::size_t n = std::size_t(nu) * std::size_t(nv);
        return n * ((9 + 1 + (bendDiagonal.empty() ? 0 : 1)) * sizeof(T) + 1);
    }
    std::int64_t at(int i, int j) const { return std::int64_t(j) * nu + start[i % 5] + i / 5; }
    std::int64_t at(std::int64_t k) const { return at(int(k % nu), int(k / nu)); }
    // How far (i + di, j + dj) lies from (i, j) here: the same for every i of one phase.
    std::int64_t offset(int i, int di, int dj) const { return at(i + di, dj + 2) - at(i, 2); }
};

// The displacements in phases, read by the grid's index k (positionAt, for addVbdStencil).
template <typename T>
struct PhasedDisplacements {
    const VbdPhases<T>& phases;
};
template <typename T>
Vec3<T> positionAt(const PhasedDisplacements<T>& d, std::int64_t k) {
    return d.phases.d.get(d.phases.at(k));
}

// vbd's contacts (docs/integrators.md "vbd", contact and friction), kept from sweep to sweep and
// step to step, one per vertex in phases' order where the solver keeps phases (the row kernel
// reads them beside the iterate), else the grid's: the unit normal n of the vertex's last
// projection, the surface's displacement over the step h v_c [m], and the friction's weight
// w = c_f λ [N] (λ the normal force that projection exerted; 0: no contact). Held only while a
// collider has friction (vbdContactCount): frictionless contact is the projection alone.
template <typename T>
struct VbdContacts {
    Soa3<T> normal, slide;
    AlignedVector<T> weight;

    // n contacts (and kVbdSlack more, read by the row kernel), none touching; those there are
    // kept where there are n already.
    void resize(std::size_t n) {
        const std::size_t entries = n > 0 ? n + std::size_t(kVbdSlack) : 0;
        if (weight.size() == entries) return;
        for (Soa3<T>* a : {&normal, &slide}) a->assign(std::int64_t(entries), Vec3<T>(0));
        weight.assign(entries, T(0));
    }
    void clear() { std::fill(weight.begin(), weight.end(), T(0)); }
    bool active() const { return !weight.empty(); }
    std::size_t bytes() const {  // the slack not counted, as VbdPhases::bytes
        return weight.empty() ? 0 : 7 * (weight.size() - std::size_t(kVbdSlack)) * sizeof(T);
    }
};

// How many contacts vbd keeps for `scene`: one per vertex where a collider has friction, else 0.
inline std::size_t vbdContactCount(const Scene& scene) {
    return scene.integrator.method == Method::Vbd && scene.anyFriction()
               ? std::size_t(scene.cloth.nu) * std::size_t(scene.cloth.nv)
               : 0;
}

}  // namespace cloth
