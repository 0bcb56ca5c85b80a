// Self-collision, a substep's share of the motion (cpu_self_collision.cpp resolve): z the
// substep's start, y moved on by uShare of the step, pins at their end pose, the sides' ref.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k == 0u) selfInts[6] = 0;  // the longest edge, taken again by self_boxes
    if (k >= selfCount()) return;
    vec3 y = selfVector(k, kSelfY);
    setSelfVector(k, kSelfZ, y);
    y += uShare * selfVector(k, kSelfStep);
    if (positions[k].w == 0.0) y = positions[k].xyz;  // pinned: at its end pose
    setSelfVector(k, kSelfY, y);
    setSelfVector(k, kSelfRef, y);
}
