// Trilinear sampling of a baked signed-distance grid (docs/colliders.md §4), the GLSL twin of
// contact(SdfColliderT) in src/model/collider_shapes.h. The including shader defines
// `float sdfValue(int index)` first (it owns the buffer the samples live in); sample (i, j, k)
// has index base + (k·ny + j)·nx + i. Returns vec4(n, φ): n is the normalised analytic gradient
// of the trilinear interpolant; outside the grid the point is clamped onto it and φ grows by the
// distance to the grid.
vec4 gridContact(vec3 pWorld, vec3 origin, float cell, ivec3 count, int base, mat3 rotation,
                 vec3 translation) {
    vec3 p = transpose(rotation) * (pWorld - translation);
    vec3 u = (p - origin) / cell;
    vec3 uc = clamp(u, vec3(0.0), vec3(count - 1));
    float away = length(u - uc) * cell;
    ivec3 i0 = min(ivec3(floor(uc)), count - 2);
    vec3 f = uc - vec3(i0);
    float phi = 0.0;
    vec3 grad = vec3(0.0);
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 d = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
        ivec3 at = i0 + d;
        float v = sdfValue(base + (at.z * count.y + at.y) * count.x + at.x);
        vec3 w = mix(vec3(1.0) - f, f, vec3(d));
        vec3 s = mix(vec3(-1.0), vec3(1.0), vec3(d));
        phi += w.x * w.y * w.z * v;
        grad += v * vec3(s.x * w.y * w.z, w.x * s.y * w.z, w.x * w.y * s.z);
    }
    float len = length(grad);
    vec3 n = len > 0.0 ? grad / len : vec3(0.0, 1.0, 0.0);
    return vec4(rotation * n, phi + away);
}
