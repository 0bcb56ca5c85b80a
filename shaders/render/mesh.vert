// A collider mesh (the unit sphere) placed by uModel.
layout(location = 0) in vec3 aPosition;

uniform mat4 uViewProj;
uniform mat4 uModel;

out vec3 vWorld;
out vec3 vNormal;

void main() {
    vec4 world = uModel * vec4(aPosition, 1.0);
    vWorld = world.xyz;
    vNormal = aPosition;  // unit sphere: position = normal (uniform scale)
    gl_Position = uViewProj * world;
}
