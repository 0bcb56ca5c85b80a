// Shared by the render shaders: one directional light plus ambient, lit from whichever side
// faces the eye (cloth is two-sided).
uniform vec3 uEye;       // [m]
uniform vec3 uLightDir;  // unit, towards the light

vec3 shade(vec3 base, vec3 normal, vec3 worldPos) {
    vec3 v = normalize(uEye - worldPos);
    vec3 n = dot(normal, v) < 0.0 ? -normal : normal;
    float diffuse = max(dot(n, uLightDir), 0.0);
    vec3 h = normalize(uLightDir + v);
    float specular = pow(max(dot(n, h), 0.0), 32.0) * 0.15;
    return base * (0.28 + 0.72 * diffuse) + vec3(specular);
}

// A normal from screen-space derivatives, for where no vertex normal exists.
vec3 facetNormal(vec3 worldPos) {
    return normalize(cross(dFdx(worldPos), dFdy(worldPos)));
}
