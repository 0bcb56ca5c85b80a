// Two-sided cloth: front (the normal's side) and back in different colours, a UV checker so
// that stretching shows, or the strain colour map; flat colour for the wireframe pass.
#include "lighting.glsl"

in vec3 vWorld;
in vec3 vNormal;
in vec2 vUv;
in float vStrain;

uniform int uColourMode;      // 0 checker, 1 strain
uniform int uFlat;            // 1: wireframe / chain lines, uFlatColour unlit
uniform vec3 uFlatColour;
uniform vec3 uFront0, uFront1, uBack0, uBack1;
uniform float uCheckers;      // squares along each side
uniform float uStrainScale;   // strain shown at full colour

out vec4 fragColour;

vec3 strainColour(float s) {
    float t = clamp(s / uStrainScale, -1.0, 1.0);
    vec3 neutral = vec3(0.92);
    return t >= 0.0 ? mix(neutral, vec3(0.85, 0.1, 0.08), t)
                    : mix(neutral, vec3(0.1, 0.3, 0.9), -t);
}

void main() {
    if (uFlat == 1) {
        fragColour = vec4(uFlatColour, 1.0);
        return;
    }
    ivec2 cell = ivec2(floor(vUv * uCheckers - 1e-4));
    bool odd = ((cell.x + cell.y) & 1) == 1;
    vec3 base = gl_FrontFacing ? (odd ? uFront1 : uFront0) : (odd ? uBack1 : uBack0);
    if (uColourMode == 1) base = strainColour(vStrain);
    vec3 n = length(vNormal) > 1e-6 ? normalize(vNormal) : facetNormal(vWorld);
    fragColour = vec4(shade(base, n, vWorld), 1.0);
}
