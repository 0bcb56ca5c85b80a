// Pass 2 (DESIGN.md §2 "Order inside one step", §3): integrate, reset pins, apply the
// colliders in scene order, and flag the first step at which anything went bad.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

// The 1-based global number of the step being taken.
layout(location = 0) uniform uint uStep;

// Mirrors gpu::Status (src/gpu/gpu_layout.h). The host reads it every few steps only.
layout(std430, binding = 7) buffer Status {
    uint firstBadStep;  // atomicMin of the step number; 0xffffffff while stable
    uint badVertex;
    uint badKind;       // 1 non-finite, 2 too fast
    float badSpeed;     // [m/s]
} status;

// DESIGN.md §2: unstable after a step that leaves a position or velocity non-finite or a speed
// above max_speed. Only the first invocation to report the earliest step writes the details.
void checkStability(uint k, vec3 p, vec3 v) {
    // As the CPU backend tests it (src/core/cpu_solver.cpp): a sum of the coordinates and |v|²
    // that overflow float count as non-finite, so both backends stop at the same step.
    float speed2 = dot(v, v);
    bool bad = nonFinite(vec3(p.x + p.y + p.z, speed2, 0.0));
    if (!bad && !(speed2 > params.integration.y)) return;
    if (atomicMin(status.firstBadStep, uStep) > uStep) {
        status.badVertex = k;
        status.badKind = bad ? 1u : 2u;
        status.badSpeed = sqrt(speed2);
    }
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;
    // Once a step went bad the state stays as it was after that step, for the host to report.
    if (status.firstBadStep < uStep) return;
    uint k = vertexIndex(ij);
    vec4 x = positions[k], v = velocities[k];
    vec3 p = x.xyz, vel = v.xyz;
    integrate(p, vel, forces[k].xyz, x.w, params.integration.x, params.gravity.w,
              params.gravity.xyz);
    // Pinned (by the scene or at run time): back to its pinned position, at rest. Compiled
    // always, since setPinned may pin any vertex; one compare of a value already loaded.
    if (x.w == 0.0) {
        p = pins[int(v.w)].xyz;
        vel = vec3(0.0);
    }
#ifdef HAS_COLLIDERS
#define PLANE(n) collidePlane(p, vel, colliders[2 * (n)].xyz, colliders[2 * (n) + 1].xyz);
#define SPHERE(n) collideSphere(p, vel, colliders[2 * NUM_PLANES + (n)]);
    COLLIDERS_IN_SCENE_ORDER
#endif
    positions[k] = vec4(p, x.w);
    velocities[k] = vec4(vel, v.w);
    checkStability(k, p, vel);
}
