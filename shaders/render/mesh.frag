#include "lighting.glsl"

in vec3 vWorld;
in vec3 vNormal;

uniform vec3 uColour;

out vec4 fragColour;

void main() { fragColour = vec4(shade(uColour, normalize(vNormal), vWorld), 1.0); }
