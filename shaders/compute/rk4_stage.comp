// rk4 (docs/integrators.md): pass 2 of stage s = 0..3, after the forces pass evaluated F at the
// stage state (x, v) in positions/velocities. Stage s adds k_{s+1} = (v, a(x, v)) to the sums and
// writes the next stage's state y_n + c k_{s+1}; the last one writes
// y_{n+1} = y_n + (h/6)(k1 + 2k2 + 2k3 + k4) and ends the step. Pinned vertices keep their pin
// (a follow pin at its end-of-step pose, with v_c) in every stage.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

layout(location = 1) uniform int uStage;  // 0..3: which k this pass computes, minus 1

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV() || frozen(uStep)) return;
    uint k = vertexIndex(ij);
    float h = params.dt;
    vec4 x = positions[k], v = velocities[k];
    vec3 a = acceleration(forces[k].xyz, v.xyz, x.w, params.dampingRate, params.gravity);
    vec3 x0, v0;
    if (uStage == 0) {
        x0 = x.xyz;
        v0 = v.xyz;
        rk4StartPositions[k] = x;
        rk4StartVelocities[k] = v;
        rk4SumPositions[k] = vec4(v.xyz, 0.0);
        rk4SumVelocities[k] = vec4(a, 0.0);
    } else {
        x0 = rk4StartPositions[k].xyz;
        v0 = rk4StartVelocities[k].xyz;
    }
    if (uStage == 3) {
        float sixth = h / 6.0;
        finishStep(uStep, k, x, v, x0 + sixth * (rk4SumPositions[k].xyz + v.xyz),
                   v0 + sixth * (rk4SumVelocities[k].xyz + a));
        return;
    }
    if (uStage > 0) {
        rk4SumPositions[k].xyz += 2.0 * v.xyz;
        rk4SumVelocities[k].xyz += 2.0 * a;
    }
    float c = uStage == 2 ? h : 0.5 * h;  // the next stage's point y_n + c k
    vec3 p = x0 + c * v.xyz, vel = v0 + c * a;
    applyPin(uStep, x, v, p, vel);
    positions[k] = vec4(p, x.w);
    velocities[k] = vec4(vel, v.w);
}
