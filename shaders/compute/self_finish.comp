// Self-collision, the step's end (cpu_self_collision.cpp resolve): the corrected positions
// become the state, the velocities change by the correction over Δt, and the state is the next
// step's start. A step that went unstable is left as it was, for the host to report.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k >= selfCount() || status.firstBadStep <= uStep) return;
    vec4 x = positions[k];
    vec3 y = selfVector(k, kSelfY), change = y - x.xyz;
    if (change != vec3(0.0)) {
        positions[k] = vec4(y, x.w);
        velocities[k].xyz += change / params.dt;
    }
    setSelfVector(k, kSelfStart, y);
}
