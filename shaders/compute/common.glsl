// Stateless physics of DESIGN.md §2: values in, force or new state out; no buffer access.
// Mirrors src/model/forces.h and src/model/colliders.h function for function.

// Force on a vertex at pk from the spring to pq (seed eq. (2)): F = K (|d| − L) d/|d|,
// d = pq − pk. A spring squeezed to (almost) zero length has no direction and adds nothing.
vec3 springForce(vec3 pk, vec3 pq, float stiffness, float restLength) {
    vec3 d = pq - pk;
    float len = length(d);
    if (!(len >= 1e-12 * restLength)) return vec3(0.0);
    return (stiffness * (len - restLength) / len) * d;
}

// Unit vertex normal from the clamped central differences a = right − left, b = up − down
// (DESIGN.md §2); 0 where |a × b| < 1e-12, so 1-D chains have no normal and feel no wind.
vec3 vertexNormal(vec3 right, vec3 left, vec3 up, vec3 down) {
    vec3 c = cross(right - left, up - down);
    float len = length(c);
    if (!(len >= 1e-12)) return vec3(0.0);
    return c / len;
}

// The viewer's grab spring (Solver::setGrab): F = K (target − x), no rest length.
vec3 grabForce(vec3 p, vec3 target, float stiffness) {
    return stiffness * (target - p);
}

#ifdef HAS_WIND
// Wind (seed §5.3): F_w = K_w ⟨n, û_w⟩ n.
vec3 windForce(vec3 normal, vec3 direction, float strength) {
    return (strength * dot(normal, direction)) * normal;
}
#endif

// a(x, v) = F(x)/m_k − c v + g of a free vertex (docs/integrators.md), 1/m_k = inverseMass, c the
// damping rate: the drag −c m_k v over m_k. As the CPU's accelerationComponent
// (src/model/spring_math.h).
vec3 acceleration(vec3 f, vec3 v, float inverseMass, float dampingRate, vec3 g) {
    return f * inverseMass - dampingRate * v + g;
}

#ifdef INTEGRATOR_EXPLICIT_EULER
// The seed's explicit Euler (DESIGN.md §2, seed eq. (6)): the position moves with the OLD
// velocity.
void integrate(inout vec3 p, inout vec3 v, vec3 f, float inverseMass, float dt, float dampingRate,
               vec3 g) {
    vec3 a = acceleration(f, v, inverseMass, dampingRate, g);
    p += dt * v;
    v += dt * a;
}
#endif

#ifdef INTEGRATOR_SYMPLECTIC_EULER
// Symplectic (semi-implicit) Euler: the position moves with the NEW velocity.
void integrate(inout vec3 p, inout vec3 v, vec3 f, float inverseMass, float dt, float dampingRate,
               vec3 g) {
    v += dt * acceleration(f, v, inverseMass, dampingRate, g);
    p += dt * v;
}
#endif

#ifdef INTEGRATOR_VERLET
// Velocity Verlet's first kick, damping at v_n, and drift: v_half = v_n + (h/2) a(x_n, v_n),
// x_{n+1} = x_n + h v_half.
void kickAndDrift(inout vec3 p, inout vec3 v, vec3 f, float inverseMass, float dt,
                  float dampingRate, vec3 g) {
    v += (0.5 * dt) * acceleration(f, v, inverseMass, dampingRate, g);
    p += dt * v;
}

// The second kick with its damping at v_{n+1} (the trapezoidal rule), solved per vertex:
// v_{n+1} = (v_half + (h/2)(F_{n+1}/m_k + g)) / (1 + hc/2).
vec3 kick(vec3 vHalf, vec3 f, float inverseMass, float dt, float dampingRate, vec3 g) {
    float halfStep = 0.5 * dt;
    return (vHalf + halfStep * (f * inverseMass + g)) / (1.0 + halfStep * dampingRate);
}
#endif

#ifdef INTEGRATOR_IMPLICIT_EULER
// J_s w for the spring from k to q, J_s = ∂F_k/∂x_q with the compressive part clamped
// (docs/integrators.md): J_s = K (d̂d̂ᵀ + max(0, 1 − L/l)(I − d̂d̂ᵀ)). Positive semi-definite;
// 0 where the spring force is (a spring squeezed to a point).
vec3 springJacobianTimes(vec3 pk, vec3 pq, float stiffness, float restLength, vec3 w) {
    vec3 d = pq - pk;
    float len = length(d);
    if (!(len >= 1e-12 * restLength)) return vec3(0.0);
    vec3 n = d / len;
    float transverse = stiffness * max(0.0, 1.0 - restLength / len);
    return transverse * w + ((stiffness - transverse) * dot(n, w)) * n;
}
#endif

// Infinity or NaN, tested on the bits: a compiler may assume finite floats in isnan/isinf.
bool nonFinite(vec3 x) {
    uvec3 exponent = floatBitsToUint(x) & 0x7f800000u;
    return any(equal(exponent, uvec3(0x7f800000u)));
}
