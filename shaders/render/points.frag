// A round marker with a dark rim.
uniform vec3 uColour;

out vec4 fragColour;

void main() {
    float r = length(gl_PointCoord - vec2(0.5));
    if (r > 0.5) discard;
    fragColour = vec4(r > 0.36 ? vec3(0.05) : uColour, 1.0);
}
