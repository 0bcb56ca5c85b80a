// Grid lines every uSpacing metres (thicker every 5), fading towards the square's edge.
#include "lighting.glsl"

in vec3 vWorld;

uniform vec3 uCentre, uTangent, uBitangent, uNormal;
uniform float uHalfSize, uSpacing;

out vec4 fragColour;

float gridLine(vec2 coord) {
    vec2 g = abs(fract(coord - 0.5) - 0.5) / fwidth(coord);
    return 1.0 - min(min(g.x, g.y), 1.0);
}

void main() {
    vec3 r = vWorld - uCentre;
    vec2 uv = vec2(dot(r, uTangent), dot(r, uBitangent));
    float minor = gridLine(uv / uSpacing), major = gridLine(uv / (5.0 * uSpacing));
    vec3 base = mix(vec3(0.42, 0.43, 0.45), vec3(0.25, 0.26, 0.28), max(minor * 0.6, major));
    float fade = 1.0 - smoothstep(0.7, 1.0, length(uv) / uHalfSize);
    vec3 lit = shade(base, uNormal, vWorld);
    fragColour = vec4(mix(vec3(0.11, 0.12, 0.15), lit, fade), 1.0);
}
