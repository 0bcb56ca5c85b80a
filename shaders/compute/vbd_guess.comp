// vbd, the initial guess (docs/integrators.md "vbd", the paper's §3.7; src/cpu/cpu_vbd.cpp
// vbdStart): d = h v_n + h² ã, x = x_n + d, ã the previous step's acceleration along gravity
// clipped to [0, |g|] (uVbd = 1), or g without a previous step (uVbd = 0); pinned vertices at
// their pin, d = pin − x_n.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

layout(location = 3) uniform int uVbd;  // 1: vbdPrevious holds v_{n−1}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    float h = params.dt, g = length(params.gravity);
    vec3 a = params.gravity;
    if (uVbd == 1 && g > 0.0) {
        float along = dot(v.xyz - vbdPrevious[k].xyz, params.gravity) / (h * g);
        a = (clamp(along, 0.0, g) / g) * params.gravity;
    }
    vec3 d = h * v.xyz + (h * h) * a, p = x.xyz + d, vel = v.xyz;
    applyPin(uStep, x, v, p, vel);
    if (x.w == 0.0) d = p - x.xyz;  // pinned
    positions[k] = vec4(p, x.w);
    vbdDisplacement[k] = vec4(d, 0.0);
    vbdPrevious[k] = vec4(v.xyz, 0.0);
    vbdBefore[k] = vec4(d, 0.0);
}
