// The cloth, drawn straight from the solver's vec4 position and normal buffers (DESIGN.md §3).
// Strain colouring reads the structural neighbours' positions from the same buffer by index.
layout(location = 0) in vec4 aPosition;  // xyz [m], w unused here
layout(location = 1) in vec4 aNormal;    // unit, 0 where undefined

layout(std430, binding = 0) readonly buffer Positions { vec4 positions[]; };

uniform mat4 uViewProj;
uniform ivec2 uGrid;      // nu, nv
uniform vec2 uRest;       // structural rest lengths along u and v [m]
uniform int uColourMode;  // 0 checker, 1 strain

out vec3 vWorld;
out vec3 vNormal;
out vec2 vUv;
out float vStrain;

bool finite3(vec3 p) { return !any(isnan(p)) && !any(isinf(p)); }

// Signed relative stretch (|d| − L)/L of the structural spring to (i+di, j+dj), 0 if absent.
float strainTo(ivec2 ij, ivec2 off, float rest) {
    ivec2 q = ij + off;
    if (rest <= 0.0 || q.x < 0 || q.y < 0 || q.x >= uGrid.x || q.y >= uGrid.y) return 0.0;
    vec3 d = positions[q.y * uGrid.x + q.x].xyz - positions[ij.y * uGrid.x + ij.x].xyz;
    return (length(d) - rest) / rest;
}

float vertexStrain(ivec2 ij) {
    float s[4] = float[4](strainTo(ij, ivec2(1, 0), uRest.x), strainTo(ij, ivec2(-1, 0), uRest.x),
                          strainTo(ij, ivec2(0, 1), uRest.y), strainTo(ij, ivec2(0, -1), uRest.y));
    float worst = 0.0;  // the largest stretch or compression, sign kept
    for (int n = 0; n < 4; ++n)
        if (abs(s[n]) > abs(worst)) worst = s[n];
    return worst;
}

void main() {
    ivec2 ij = ivec2(gl_VertexID % uGrid.x, gl_VertexID / uGrid.x);
    vec3 p = aPosition.xyz;
    vWorld = p;
    vNormal = aNormal.xyz;
    vUv = vec2(uGrid.x > 1 ? float(ij.x) / float(uGrid.x - 1) : 0.0,
               uGrid.y > 1 ? float(ij.y) / float(uGrid.y - 1) : 0.0);
    vStrain = uColourMode == 1 ? vertexStrain(ij) : 0.0;
    // Never draw a non-finite vertex: put it outside the clip volume.
    gl_Position = finite3(p) ? uViewProj * vec4(p, 1.0) : vec4(0.0, 0.0, 2.0, 1.0);
}
