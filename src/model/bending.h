// The bending energy of a material (docs/physics.md "Bending"): quadratic in the positions,
// so its force is linear and its Hessian constant, and its stencil lies inside the 12-neighbour
// gather of the springs:
//
//   E = ½ Σ_{vertices with both u-neighbours} w_u(j) |x_{i−1,j} − 2x_{i,j} + x_{i+1,j}|²
//     + ½ Σ_{vertices with both v-neighbours} w_v(i) |x_{i,j−1} − 2x_{i,j} + x_{i,j+1}|²
//     + ½ Σ_{cells} t |x_{i,j} − x_{i+1,j} − x_{i,j+1} + x_{i+1,j+1}|²
//
//   w_u(j) = B·dv·s_j / du³,  w_v(i) = B·du·s_i / dv³,  t = 2B / (du·dv)
//
// (s = ½ on a side's first and last index, else 1: each second difference stands for its
// vertex's share of the width.) It is the energy ½B∫(w_uu² + 2w_uv² + w_vv²) of a plate with
// Poisson ratio 0, discretised; an affine map of the grid (a rigid motion, a uniform stretch)
// costs nothing, so a flat sheet at rest has none. Force F = −∂E/∂x, and H p = −F(p): the same
// stencil applied to any vector.
#pragma once

#include "model/grid.h"
#include "model/spring_math.h"

namespace cloth {

struct BendingWeights {
    int nu = 0, nv = 0;
    double alongU = 0, alongV = 0;  // B·dv/du³ and B·du/dv³ [N/m]: w_u, w_v inside the sheet
    double twist = 0;               // t = 2B/(du·dv) [N/m]
    bool active() const { return twist > 0; }
    // The side share s of index n of `count`: ½ at either end.
    static double share(int n, int count) { return n == 0 || n == count - 1 ? 0.5 : 1.0; }
};

// B [N·m] on the grid g; all zero (not modelled) when B = 0 or a side has fewer than 2 vertices.
inline BendingWeights bendingWeights(const Grid& g, double bend) {
    BendingWeights w;
    w.nu = g.nu;
    w.nv = g.nv;
    if (!(bend > 0) || g.nu < 2 || g.nv < 2) return w;
    w.alongU = bend * g.dv / (g.du * g.du * g.du);
    w.alongV = bend * g.du / (g.dv * g.dv * g.dv);
    w.twist = 2 * bend / (g.du * g.dv);
    return w;
}

// −∂E/∂x at vertex (i, j); x(i, j) reads a position (or any vector: the Hessian product). Every
// stencil that contains the vertex contributes: the second differences centred at it and at its
// two neighbours along each axis (coefficients 1, −2, 1), and the twists of its up to four cells.
template <typename T, typename At>
Vec3<T> bendingForce(const BendingWeights& w, int i, int j, const At& x) {
    Vec3<T> f(0);
    const T wu = T(w.alongU * BendingWeights::share(j, w.nv));
    const T wv = T(w.alongV * BendingWeights::share(i, w.nu));
    for (int c = -1; c <= 1; ++c) {
        const T coefficient = c == 0 ? T(-2) : T(1);
        const int ic = i + c, jc = j + c;
        if (ic >= 1 && ic <= w.nu - 2) {
            const Vec3<T> d = x(ic - 1, j) - T(2) * x(ic, j) + x(ic + 1, j);
            f -= (wu * coefficient) * d;
        }
        if (jc >= 1 && jc <= w.nv - 2) {
            const Vec3<T> d = x(i, jc - 1) - T(2) * x(i, jc) + x(i, jc + 1);
            f -= (wv * coefficient) * d;
        }
    }
    const T t = T(w.twist);
    for (int a = i - 1; a <= i; ++a) {
        if (a < 0 || a > w.nu - 2) continue;
        for (int b = j - 1; b <= j; ++b) {
            if (b < 0 || b > w.nv - 2) continue;
            const Vec3<T> twist = x(a, b) - x(a + 1, b) - x(a, b + 1) + x(a + 1, b + 1);
            const T sign = T((a == i ? 1 : -1) * (b == j ? 1 : -1));
            f -= (t * sign) * twist;
        }
    }
    return f;
}

// bendingForce on one component at an interior vertex, for the row kernels (cpu/isa/: the
// vectorised bending force, vbd's local problems), from its 13 stencil values: row j's five
// u0…u4 (columns i − 2 … i + 2), rows j ± 1's three each (l… below, h… above: columns i − 1, i,
// i + 1), rows j ± 2's one each. The weights come as bendingForce's products: u1 = w_u·1,
// u0 = w_u·(−2), v1, v0 likewise, and the twist's plus = t·1, minus = t·(−1). bendingForce's
// order: the second differences along u and v centred at i − 1, i, i + 1 (j − 1, j, j + 1),
// then the twists of the cells (i − 1, j − 1), (i − 1, j), (i, j − 1), (i, j).
template <typename T>
CLOTH_LANE T bendingLane(T u0_, T u1_, T u2_, T u3_, T u4_, T l0, T l1, T l2, T h0, T h1, T h2,
                         T down, T up, T u1, T u0, T v1, T v0, T plus, T minus) {
    const T two = T(2);
    T b = T(0);
    b -= u1 * ((u0_ - two * u1_) + u2_);
    b -= v1 * ((down - two * l1) + u2_);
    b -= u0 * ((u1_ - two * u2_) + u3_);
    b -= v0 * ((l1 - two * u2_) + h1);
    b -= u1 * ((u2_ - two * u3_) + u4_);
    b -= v1 * ((u2_ - two * h1) + up);
    b -= plus * (((l0 - l1) - u1_) + u2_);
    b -= minus * (((u1_ - u2_) - h0) + h1);
    b -= minus * (((l1 - l2) - u2_) + u3_);
    b -= plus * (((u2_ - u3_) - h1) + h2);
    return b;
}

// E of the positions x(i, j) [J]: what bendingForce is minus the gradient of.
template <typename At>
double bendingEnergy(const BendingWeights& w, const At& x) {
    double e = 0;
    for (int j = 0; j < w.nv; ++j)
        for (int i = 0; i < w.nu; ++i) {
            if (i >= 1 && i <= w.nu - 2) {
                const auto d = x(i - 1, j) - 2.0 * x(i, j) + x(i + 1, j);
                e += 0.5 * w.alongU * BendingWeights::share(j, w.nv) * glm::dot(d, d);
            }
            if (j >= 1 && j <= w.nv - 2) {
                const auto d = x(i, j - 1) - 2.0 * x(i, j) + x(i, j + 1);
                e += 0.5 * w.alongV * BendingWeights::share(i, w.nu) * glm::dot(d, d);
            }
            if (i <= w.nu - 2 && j <= w.nv - 2) {
                const auto t = x(i, j) - x(i + 1, j) - x(i, j + 1) + x(i + 1, j + 1);
                e += 0.5 * w.twist * glm::dot(t, t);
            }
        }
    return e;
}

// Gershgorin's bound on the bending Hessian's eigenvalues: a vertex's row of W has absolute sum
// at most 16·w_u (the interior row b·[1, −4, 6, −4, 1] twice over) + 16·w_v + 16·t.
inline double bendingLambdaBound(const BendingWeights& w) {
    return 16 * (w.alongU + w.alongV + w.twist);
}

}  // namespace cloth
