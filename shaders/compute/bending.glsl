// The bending energy of a material (HAS_BENDING), mirroring src/model/bending.h: −∂E/∂x at a
// vertex from the second differences along u and v centred at it and at its neighbours
// (coefficients 1, −2, 1) and the twists of its up to four cells. The energy is quadratic, so
// the same stencil applied to any vector field is the Hessian product H w = −F(w). The including
// kernel #defines BENDING_FIELD(q) as the field the stencil reads at grid point q: the positions
// for the force, the vector H multiplies for the implicit solve.

float bendingShare(int n, int count) { return n == 0 || n == count - 1 ? 0.5 : 1.0; }

// The bending Hessian's diagonal coefficient at ij: each second difference and twist that holds
// the vertex, weighted by the square of its coefficient there (−bendingForce of a field that is
// 1 at ij alone; src/model/implicit_system.h takes it that way).
float bendingDiagonal(ivec2 ij, vec3 weights) {
    int i = ij.x, j = ij.y, nu = gridU(), nv = gridV();
    float h = 0.0;
    for (int c = -1; c <= 1; ++c) {
        float squared = c == 0 ? 4.0 : 1.0;
        if (i + c >= 1 && i + c <= nu - 2) h += weights.x * bendingShare(j, nv) * squared;
        if (j + c >= 1 && j + c <= nv - 2) h += weights.y * bendingShare(i, nu) * squared;
    }
    for (int a = i - 1; a <= i; ++a)
        for (int b = j - 1; b <= j; ++b)
            if (a >= 0 && a <= nu - 2 && b >= 0 && b <= nv - 2) h += weights.z;
    return h;
}

// weights = (w_u, w_v, t) of bending.h inside the sheet: B·dv/du³, B·du/dv³, 2B/(du·dv) [N/m].
vec3 bendingForce(ivec2 ij, vec3 weights) {
    int i = ij.x, j = ij.y, nu = gridU(), nv = gridV();
    float wu = weights.x * bendingShare(j, nv);
    float wv = weights.y * bendingShare(i, nu);
    vec3 f = vec3(0.0);
    for (int c = -1; c <= 1; ++c) {
        float coefficient = c == 0 ? -2.0 : 1.0;
        int ic = i + c, jc = j + c;
        if (ic >= 1 && ic <= nu - 2) {
            vec3 d = BENDING_FIELD(ivec2(ic - 1, j)) - 2.0 * BENDING_FIELD(ivec2(ic, j)) +
                     BENDING_FIELD(ivec2(ic + 1, j));
            f -= (wu * coefficient) * d;
        }
        if (jc >= 1 && jc <= nv - 2) {
            vec3 d = BENDING_FIELD(ivec2(i, jc - 1)) - 2.0 * BENDING_FIELD(ivec2(i, jc)) +
                     BENDING_FIELD(ivec2(i, jc + 1));
            f -= (wv * coefficient) * d;
        }
    }
    for (int a = i - 1; a <= i; ++a) {
        if (a < 0 || a > nu - 2) continue;
        for (int b = j - 1; b <= j; ++b) {
            if (b < 0 || b > nv - 2) continue;
            vec3 twist = BENDING_FIELD(ivec2(a, b)) - BENDING_FIELD(ivec2(a + 1, b)) -
                         BENDING_FIELD(ivec2(a, b + 1)) + BENDING_FIELD(ivec2(a + 1, b + 1));
            float sign = float((a == i ? 1 : -1) * (b == j ? 1 : -1));
            f -= (weights.z * sign) * twist;
        }
    }
    return f;
}
