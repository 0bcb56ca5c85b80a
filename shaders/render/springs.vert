// Spring overlay: the 12 springs of vertex uCentre, two line vertices each, positions read from
// the solver's buffer by index. Offsets outside the grid or of an unmodelled family collapse to
// a point. uMode 1 draws instead one line from uCentre to uTarget (the grab spring).
layout(std430, binding = 0) readonly buffer Positions { vec4 positions[]; };

uniform mat4 uViewProj;
uniform ivec2 uGrid;
uniform int uCentre;
uniform ivec3 uOffsets[12];  // di, dj, family (0 structural, 1 shear, 2 bend)
uniform ivec3 uFamilyOn;     // 1 where the scene models the family
uniform vec3 uFamilyColour[3];
uniform int uMode;
uniform vec3 uTarget;

out vec3 vColour;

void main() {
    // Bend springs first, structural last: a bend spring runs along two structural ones, which
    // stay visible on top of it.
    int spring = 11 - gl_VertexID / 2;
    bool far = (gl_VertexID & 1) == 1;
    ivec2 ij = ivec2(uCentre % uGrid.x, uCentre / uGrid.x);
    vec3 p = positions[uCentre].xyz;
    if (uMode == 1) {
        vColour = vec3(1.0, 0.95, 0.3);
        if (far) p = uTarget;
    } else {
        ivec3 o = uOffsets[spring];
        ivec2 q = ij + o.xy;
        bool exists = q.x >= 0 && q.y >= 0 && q.x < uGrid.x && q.y < uGrid.y && uFamilyOn[o.z] == 1;
        vColour = uFamilyColour[o.z];
        if (far && exists) p = positions[q.y * uGrid.x + q.x].xyz;
    }
    gl_Position = uViewProj * vec4(p, 1.0);
}
