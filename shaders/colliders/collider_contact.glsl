// The contact response every collider shares (docs/colliders.md §2), the GLSL twin of
// src/model/collider_contact.h: push out to the thickness h, remove the normal part of the
// velocity relative to the collider (v_c), Coulomb friction takes at most c_f·|w_n| from the
// tangential part, static (v = v_c) when that would reverse it.

void respondVelocity(inout vec3 v, vec3 n, vec3 vc, float friction) {
    vec3 w = v - vc;
    float wn = dot(w, n);
    v -= wn * n;
    if (!(friction > 0.0)) return;
    vec3 wt = w - wn * n;
    float wtLen = length(wt);
    float budget = friction * abs(wn);
    if (wtLen <= budget)
        v = vc;
    else
        v -= (budget / wtLen) * wt;
}

// c = vec4(n, φ) from a *Contact function; true when the vertex was in contact (φ < h).
bool respondContact(vec4 c, float thickness, float friction, vec3 vc, inout vec3 p, inout vec3 v) {
    if (!(c.w < thickness)) return false;
    p += (thickness - c.w) * c.xyz;
    respondVelocity(v, c.xyz, vc, friction);
    return true;
}

#ifdef HAS_CONTACT_SPHERES
// The sphere lands on its shell: p = c + (R + h) n (DESIGN.md §2's c + R n when h = 0).
bool respondSphere(vec3 center, float radius, float thickness, float friction, vec3 vc,
                   inout vec3 p, inout vec3 v) {
    vec4 c = sphereContact(p, center, radius);
    if (!(c.w < thickness)) return false;
    p = center + (radius + thickness) * c.xyz;
    respondVelocity(v, c.xyz, vc, friction);
    return true;
}
#endif
