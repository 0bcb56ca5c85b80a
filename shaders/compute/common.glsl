// Stateless physics of DESIGN.md §2: values in, force or new state out; no buffer access.
// Mirrors src/core/forces.h and src/core/colliders.h function for function.

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

#ifdef INTEGRATOR_EXPLICIT_EULER
// The seed's explicit Euler (DESIGN.md §2, seed eq. (6)): the position moves with the OLD
// velocity; a = (F − μ v)/m + g.
void integrate(inout vec3 p, inout vec3 v, vec3 f, float inverseMass, float dt, float damping,
               vec3 g) {
    vec3 a = (f - damping * v) * inverseMass + g;
    p += dt * v;
    v += dt * a;
}
#endif

#ifdef HAS_PLANES
// Seed Q12: s = ⟨p − c, n̂⟩; below the plane, p ← p − s n̂ and v ← v − ⟨v, n̂⟩ n̂.
void collidePlane(inout vec3 p, inout vec3 v, vec3 point, vec3 normal) {
    float s = dot(p - point, normal);
    if (s < 0.0) {
        p -= s * normal;
        v -= dot(v, normal) * normal;
    }
}
#endif

#ifdef HAS_SPHERES
// Seed Q13: inside the sphere, p ← c + R n̂, v ← v − ⟨v, n̂⟩ n̂, n̂ = (p − c)/|p − c|
// ((0, 1, 0) at the very centre): the cloth slides on the surface.
void collideSphere(inout vec3 p, inout vec3 v, vec4 sphere) {
    vec3 r = p - sphere.xyz;
    float len = length(r);
    if (len < sphere.w) {
        vec3 n = len > 0.0 ? r / len : vec3(0.0, 1.0, 0.0);
        p = sphere.xyz + sphere.w * n;
        v -= dot(v, n) * n;
    }
}
#endif

// Infinity or NaN, tested on the bits: a compiler may assume finite floats in isnan/isinf.
bool nonFinite(vec3 x) {
    uvec3 exponent = floatBitsToUint(x) & 0x7f800000u;
    return any(equal(exponent, uvec3(0x7f800000u)));
}
