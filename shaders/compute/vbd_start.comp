// vbd, the step's start (docs/integrators.md "vbd"; src/cpu/cpu_vbd.cpp vbdStart): the inertial
// target's displacement ŷ = h v_n + h² (g + F_w(x_n)/m), the wind from the normals of x_n, which
// it writes for the renderer (vbd has no force pass).
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#ifdef HAS_WIND
float windStrengthAt(ivec2 ij) {  // forces.glsl's, without the rest of the force pass
    float s = params.windStrength;
#ifdef HAS_BORDER_SHARES
    if (ij.x == 0 || ij.x == gridU() - 1) s *= 0.5;
    if (ij.y == 0 || ij.y == gridV() - 1) s *= 0.5;
#endif
    return s;
}
#endif

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;
    uint k = vertexIndex(ij);
    vec3 a = params.gravity;
    int i = ij.x, j = ij.y;
    vec3 n = vertexNormal(positions[vertexIndex(ivec2(min(i + 1, gridU() - 1), j))].xyz,
                          positions[vertexIndex(ivec2(max(i - 1, 0), j))].xyz,
                          positions[vertexIndex(ivec2(i, min(j + 1, gridV() - 1)))].xyz,
                          positions[vertexIndex(ivec2(i, max(j - 1, 0)))].xyz);
    normals[k] = vec4(n, 0.0);  // the renderer's, as the other integrators' force pass writes them
#ifdef HAS_WIND
    a += positions[k].w * windForce(n, params.windDirection, windStrengthAt(ij));
#endif
    float h = params.dt;
    vbdInertial[k] = vec4(h * velocities[k].xyz + (h * h) * a, 0.0);
}
