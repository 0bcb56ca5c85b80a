// A symmetric 3×3 matrix by its six entries: the diagonal blocks of implicit Euler's system (its
// block-Jacobi preconditioner, docs/integrators.md) and VBD's local Hessians (model/vbd_local.h).
// Every term of either is a multiple of I or of an outer product d dᵀ, so half of a full
// matrix's sums are never needed.
#pragma once

#include <cmath>

#include "model/grid.h"

namespace cloth {

template <typename T>
struct Sym3 {
    T xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;

    static Sym3 identity(T s) { return {s, s, s, 0, 0, 0}; }
    // a·n nᵀ
    static Sym3 outer(const Vec3<T>& n, T a) {
        return {a * n.x * n.x, a * n.y * n.y, a * n.z * n.z,
                a * n.x * n.y, a * n.x * n.z, a * n.y * n.z};
    }
    void addDiagonal(T s) {
        xx += s;
        yy += s;
        zz += s;
    }
    void addOuter(T c, const Vec3<T>& d) {  // += c d dᵀ
        const Vec3<T> cd = c * d;
        xx += cd.x * d.x;
        xy += cd.x * d.y;
        xz += cd.x * d.z;
        yy += cd.y * d.y;
        yz += cd.y * d.z;
        zz += cd.z * d.z;
    }
    glm::dmat3 matrix() const { return glm::dmat3(xx, xy, xz, xy, yy, yz, xz, yz, zz); }
    Sym3& operator+=(const Sym3& o) {
        xx += o.xx, yy += o.yy, zz += o.zz, xy += o.xy, xz += o.xz, yz += o.yz;
        return *this;
    }
    Sym3 operator*(T s) const { return {xx * s, yy * s, zz * s, xy * s, xz * s, yz * s}; }
    Vec3<T> operator*(const Vec3<T>& w) const {
        return {xx * w.x + xy * w.y + xz * w.z, xy * w.x + yy * w.y + yz * w.z,
                xz * w.x + yz * w.y + zz * w.z};
    }
    T determinant() const {
        return xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz);
    }
    // The inverse by the adjugate; 0 (no step) where the matrix is singular or not finite.
    Sym3 inverse() const {
        const T det = determinant();
        if (!(std::abs(det) > T(0)) || !std::isfinite(det)) return {};
        const T s = T(1) / det;
        return {(yy * zz - yz * yz) * s, (xx * zz - xz * xz) * s, (xx * yy - xy * xy) * s,
                (xz * yz - xy * zz) * s, (xy * yz - xz * yy) * s, (xy * xz - xx * yz) * s};
    }
};

}  // namespace cloth
