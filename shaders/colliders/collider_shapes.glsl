// Signed distance φ and outward unit normal n of the collider shapes (docs/colliders.md §1): the
// GLSL twin of src/model/collider_shapes.h, function for function, checked against it by
// tests/gpu/gpu_colliders_test.cpp. Each returns vec4(n, φ); inside is negative. A shape is
// compiled where the includer defines its HAS_CONTACT_PLANES, HAS_CONTACT_SPHERES, HAS_BOXES or
// HAS_CAPSULES (the solver's kernels: the scene's shapes only, DESIGN.md §3).

#ifdef HAS_CONTACT_PLANES
// DESIGN.md §2: s = ⟨p − c, n̂⟩.
vec4 planeContact(vec3 p, vec3 point, vec3 normal) {
    return vec4(normal, dot(p - point, normal));
}
#endif

#ifdef HAS_CONTACT_SPHERES
// n = (p − c)/|p − c|, (0, 1, 0) at the very centre.
vec4 sphereContact(vec3 p, vec3 center, float radius) {
    vec3 r = p - center;
    float len = length(r);
    return vec4(len > 0.0 ? r / len : vec3(0.0, 1.0, 0.0), len - radius);
}
#endif

#ifdef HAS_BOXES
// The exact SDF of an oriented box; `rotation` maps box axes to world (its columns). Outside:
// the distance to the clamped point; inside: minus the distance to the nearest face (the first
// of equal ones, x before y before z); sign(0) = +1.
vec4 boxContact(vec3 p, vec3 center, vec3 halfExtents, mat3 rotation) {
    vec3 q = transpose(rotation) * (p - center);
    vec3 s = vec3(q.x < 0.0 ? -1.0 : 1.0, q.y < 0.0 ? -1.0 : 1.0, q.z < 0.0 ? -1.0 : 1.0);
    vec3 d = abs(q) - halfExtents;
    vec3 outside = max(d, vec3(0.0));
    float outLen = length(outside);
    if (outLen > 0.0) return vec4(rotation * (s * outside / outLen), outLen);
    int axis = 0;
    if (d.y > d[axis]) axis = 1;
    if (d.z > d[axis]) axis = 2;
    vec3 n = vec3(0.0);
    n[axis] = s[axis];
    return vec4(rotation * n, d[axis]);
}
#endif

#ifdef HAS_CAPSULES
// φ = |p − q| − R, q the point of segment ab nearest p; on the axis, a fixed perpendicular.
vec4 capsuleContact(vec3 p, vec3 a, vec3 b, float radius) {
    vec3 ab = b - a;
    float len2 = dot(ab, ab);
    float t = len2 > 0.0 ? clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    vec3 r = p - (a + t * ab);
    float len = length(r);
    if (len > 0.0) return vec4(r / len, len - radius);
    if (len2 == 0.0) return vec4(0.0, 1.0, 0.0, -radius);
    vec3 u = abs(ab);
    vec3 e = u.x <= u.y && u.x <= u.z ? vec3(1.0, 0.0, 0.0)
           : (u.y <= u.z ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0));
    return vec4(normalize(cross(ab, e)), -radius);
}
#endif
