// vbd's end of step (docs/integrators.md "vbd"): v_{n+1} = d/h, then pins, colliders and
// the instability check. A vertex that started inside a collider keeps none of the correction
// that put it out as velocity (src/model/start_inside.h withoutStartCorrection).
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#ifdef HAS_CONTACT
vec3 withoutStartCorrection(vec3 start, vec3 v, float h) {
    vec3 q = start, w = vec3(0.0);
    applyColliders(uStep, q, w);
    vec3 d = q - start;
    float depth = length(d);
    if (!(depth > 0.0)) return v;
    vec3 n = d / depth, vc = colliderSurfaceVelocity(uStep, start);
    float excess = depth / h - dot(n, vc), away = dot(n, v - vc);
    return v - min(max(excess, 0.0), max(away, 0.0)) * n;
}
#endif

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 d = vbdDisplacement[k].xyz, vel = d / params.dt;
#ifdef HAS_CONTACT
    if (x.w != 0.0) vel = withoutStartCorrection(x.xyz - d, vel, params.dt);
#endif
    finishStep(uStep, k, x, v, x.xyz, vel);
}
