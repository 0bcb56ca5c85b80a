// vbd's local problem (docs/integrators.md "vbd"), mirroring src/model/vbd_local.h function for
// function: the gradient and Hessian of one vertex's part of backward Euler's incremental
// potential, and the 3×3 Newton step on it. The Hessian is kept as its six entries (Sym3).

struct VbdLocal {
    vec3 gradient;
    vec3 diagonal;   // xx, yy, zz
    vec3 offDiagonal;  // xy, xz, yz
};

VbdLocal vbdLocalZero() { return VbdLocal(vec3(0.0), vec3(0.0), vec3(0.0)); }

void addDiagonal(inout VbdLocal l, float s) { l.diagonal += vec3(s); }

void addOuter(inout VbdLocal l, float c, vec3 d) {  // += c d dᵀ
    vec3 cd = c * d;
    l.diagonal += cd * d;
    l.offDiagonal += vec3(cd.x * d.y, cd.x * d.z, cd.y * d.z);
}

// Inertia and air drag on the displacement d = x − x_n: m/(2h²)|d − ŷ|² + m c/(2h)|d|²,
// ŷ = y − x_n (addVbdInertia).
void addVbdInertia(inout VbdLocal l, vec3 d, vec3 target, float mass, float h,
                   float dampingRate) {
    float inertia = mass / (h * h), drag = mass * dampingRate / h;
    l.gradient += inertia * (d - target) + drag * d;
    addDiagonal(l, inertia + drag);
}

// The spring from k to q (addVbdSpring): gradient −springForce, Hessian the clamped J_s.
void addVbdSpring(inout VbdLocal l, vec3 pk, vec3 pq, float stiffness, float restLength) {
    vec3 d = pq - pk;
    float len = length(d);
    if (!(len >= 1e-12 * restLength)) return;
    l.gradient -= (stiffness * (len - restLength) / len) * d;
    float transverse = stiffness * max(0.0, 1.0 - restLength / len);
    addDiagonal(l, transverse);
    addOuter(l, (stiffness - transverse) / (len * len), d);
}

#ifdef HAS_SPRING_DAMPING
// Implicit Euler's D on the step's displacement (addVbdSpringDamping): w = Δ_q − Δ_k, the ends
// at x_n: d = e − w, e = x_q − x_k now.
void addVbdSpringDamping(inout VbdLocal l, vec3 e, vec3 w, float dampingK, float restLength,
                         float h) {
    vec3 d = e - w;
    l.gradient -= springDampingForce(d, w, dampingK, restLength) / h;
    float d2 = dot(d, d), floorLength = 1e-12 * restLength;
    if (d2 >= floorLength * floorLength) addOuter(l, dampingK / (h * d2), d);
}
#endif

#ifdef HAS_BENDING
// W_kk (bendingDiagonal): the squares of the vertex's coefficients in every second difference
// (1, −2, 1) and twist (±1) that holds it, times their weights.
float vbdBendingDiagonal(ivec2 ij, vec3 weights) {
    int i = ij.x, j = ij.y, nu = gridU(), nv = gridV();
    float wu = weights.x * bendingShare(j, nv), wv = weights.y * bendingShare(i, nu);
    float w = 0.0;
    for (int c = -1; c <= 1; ++c) {
        float square = c == 0 ? 4.0 : 1.0;
        if (i + c >= 1 && i + c <= nu - 2) w += wu * square;
        if (j + c >= 1 && j + c <= nv - 2) w += wv * square;
    }
    for (int a = i - 1; a <= i; ++a)
        for (int b = j - 1; b <= j; ++b)
            if (a >= 0 && a <= nu - 2 && b >= 0 && b <= nv - 2) w += weights.z;
    return w;
}
#endif

#ifdef HAS_COLLIDERS
// ε_v [m/s] (kVbdStickSpeed): below this slide speed against the surface friction holds.
#define VBD_STICK_SPEED 1e-3

// Friction as an energy with the lagged normal force (vbdFrictionLane): u = d − h v_c,
// n and w = c_f λ of the vertex's last projection, ε = ε_v h; g += s S u, H += s S with
// s = w f1(|S u|)/|S u|.
void addVbdFriction(inout VbdLocal l, vec3 u, vec3 n, float weight, float epsilon) {
    vec3 t = u - dot(u, n) * n;
    float slide = length(t);
    float ratio = slide < epsilon ? (2.0 - slide / epsilon) / epsilon : 1.0 / slide;
    float s = weight * ratio;
    l.gradient += s * t;
    addDiagonal(l, s);
    addOuter(l, -s, n);
}

// nᵀ H n (vbdNormalStiffness).
float vbdNormalStiffness(VbdLocal l, vec3 n) {
    vec3 o = l.offDiagonal;
    return dot(l.diagonal, n * n) + 2.0 * (o.x * n.x * n.y + o.y * n.x * n.z + o.z * n.y * n.z);
}
#endif

// s = −H⁻¹g by the adjugate (vbdNewtonStep, in float here), for the caller to add to x and d; a
// step with det H ≤ 1e-12·floor³ (H ⪰ floor·I, floor = m/h²) is skipped. Returns whether it
// moved.
bool vbdNewtonStep(VbdLocal l, float floor, out vec3 s) {
    s = vec3(0.0);
    vec3 dg = l.diagonal, o = l.offDiagonal;  // o = (xy, xz, yz)
    float c00 = dg.y * dg.z - o.z * o.z, c01 = o.y * o.z - o.x * dg.z, c02 = o.x * o.z - o.y * dg.y;
    float det = dg.x * c00 + o.x * c01 + o.y * c02;
    if (!(abs(det) > 1e-12 * floor * floor * floor)) return false;
    float c11 = dg.x * dg.z - o.y * o.y, c12 = o.x * o.y - dg.x * o.z;
    float c22 = dg.x * dg.y - o.x * o.x;
    vec3 g = l.gradient;
    s = -vec3(c00 * g.x + c01 * g.y + c02 * g.z, c01 * g.x + c11 * g.y + c12 * g.z,
              c02 * g.x + c12 * g.y + c22 * g.z) / det;
    return true;
}
