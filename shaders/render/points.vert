// Markers (pinned vertices, chain vertices) at cloth vertices, from the position buffer.
layout(location = 0) in vec4 aPosition;

uniform mat4 uViewProj;
uniform float uPointSize;  // [px]

void main() {
    gl_PointSize = uPointSize;
    gl_Position = uViewProj * vec4(aPosition.xyz, 1.0);
}
