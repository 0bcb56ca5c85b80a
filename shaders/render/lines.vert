// Coloured line segments from a small vertex buffer (wind arrow, grab target).
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aColour;

uniform mat4 uViewProj;

out vec3 vColour;

void main() {
    vColour = aColour;
    gl_Position = uViewProj * vec4(aPosition, 1.0);
}
