// A plane collider as a square of side 2·uHalfSize around uCentre, spanned by uTangent and
// uBitangent; four vertices from gl_VertexID (triangle strip), no buffer.
uniform mat4 uViewProj;
uniform vec3 uCentre, uTangent, uBitangent;
uniform float uHalfSize;  // [m]

out vec3 vWorld;

void main() {
    vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1) * 2.0 - 1.0;
    vWorld = uCentre + uHalfSize * (corner.x * uTangent + corner.y * uBitangent);
    gl_Position = uViewProj * vec4(vWorld, 1.0);
}
