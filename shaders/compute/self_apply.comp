// Self-collision, an iteration's end (cpu_self_collision.cpp correct): each vertex takes the
// mean of its contacts' corrections, then the colliders' position projection; the sums are
// emptied for the next iteration.
#include "layout.glsl"
#include "common.glsl"
#include "step_end.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k == 0u) selfInts[6] = 0;  // the longest edge, taken again by self_boxes
    if (k >= selfCount()) return;
    uint at = selfSums() + 4u * k;
    int touches = selfInts[at + 3u];
    if (touches == 0) return;
    vec3 sum = vec3(selfInts[at], selfInts[at + 1u], selfInts[at + 2u]);
    vec3 y = selfVector(k, kSelfY) + sum / (uFixedScale * float(touches));
#ifdef HAS_COLLIDERS
    vec3 unused = vec3(0.0);
    applyColliders(uStep, y, unused);
#endif
    setSelfVector(k, kSelfY, y);
    selfInts[selfFlags() + k] = 1;
    for (uint c = 0u; c < 4u; ++c) selfInts[at + c] = 0;
}
