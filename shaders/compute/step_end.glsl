// What every scheme does at the end of its step (DESIGN.md §2 "Order inside one step",
// docs/integrators.md): pins, then the colliders in scene order, then the instability check.
// Included by the kernels that write the state.

// The 1-based global number of the step being taken; many_steps.comp: the first of its steps.
// The functions below take the step as an argument so that many_steps.comp can count on.
layout(location = 2) uniform uint uStep;

// Mirrors gpu::Status (src/gpu/gpu_layout.h). The host reads it every few steps only.
layout(std430, binding = 7) STATE_COHERENT buffer Status {
    uint firstBadStep;  // atomicMin of the step number; 0xffffffff while stable
    uint badVertex;     // atomicMin of the bad vertices' k at that step; 0xffffffff before
} status;

// Once a step went bad the state stays as it was after that step, for the host to report.
bool frozen(uint step) { return status.firstBadStep < step; }

// DESIGN.md §2: unstable after a step that leaves a position or velocity non-finite or a speed
// above max_speed. Every vertex bad at the earliest step offers its k and the lowest stays, the
// vertex the CPU reports (the first in grid order), whatever order the invocations run in; the
// host reads its kind and speed from the state, which that step left as it is.
void checkStability(uint step, uint k, vec3 p, vec3 v) {
    // As the CPU backend tests it (src/cpu/cpu_solver.cpp): a sum of the coordinates and |v|²
    // that overflow float count as non-finite, so both backends stop at the same step.
    float speed2 = dot(v, v);
    bool bad = nonFinite(vec3(p.x + p.y + p.z, speed2, 0.0));
    if (!bad && !(speed2 > params.maxSpeedSquared)) return;
    if (atomicMin(status.firstBadStep, step) >= step) atomicMin(status.badVertex, k);
}

#ifdef HAS_COLLIDERS
#include "scene_colliders.glsl"
#endif

// A pinned vertex (by the scene or at run time: position.w = 0) goes back to its pinned
// position, at rest; one that follows a collider (the pin's w > 0: its FollowRecord's offset + 1
// in the pose slot) to where the collider's motion carries it at the end of step `step`, with
// its velocity. Compiled always, since setPinned may pin any vertex; one compare of a value
// already loaded. x, v: the vertex's stored vec4s (w: inverse mass, pin slot).
void applyPin(uint step, vec4 x, vec4 v, inout vec3 p, inout vec3 vel) {
    if (x.w == 0.0) {
        vec4 pin = pins[int(v.w)];
        p = pin.xyz;
        vel = vec3(0.0);
#ifdef HAS_FOLLOW_PINS
        if (pin.w > 0.0) followPin(step, int(pin.w) - 1, pin.xyz, p, vel);
#endif
    }
}

// The scheme's new (p, vel) of vertex k at step `step`: pins, colliders, store (keeping the w of x and v),
// check.
void finishStep(uint step, uint k, vec4 x, vec4 v, vec3 p, vec3 vel) {
    applyPin(step, x, v, p, vel);
#ifdef HAS_COLLIDERS
    applyColliders(step, p, vel);
#endif
    positions[k] = vec4(p, x.w);
    velocities[k] = vec4(vel, v.w);
    checkStability(step, k, p, vel);
}
