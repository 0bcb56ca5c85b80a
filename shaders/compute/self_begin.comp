// Self-collision, the step's start (cpu_self_collision.cpp resolve, chooseSubsteps): the motion
// x₁ − x₀ of every vertex and its bounding box in the header (the host reads it for the
// substeps), y back to x₀, no vertex in contact yet.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k >= selfCount()) return;
    vec3 start = selfVector(k, kSelfStart), step = positions[k].xyz - start;
    setSelfVector(k, kSelfStep, step);
    setSelfVector(k, kSelfY, start);
    selfInts[selfFlags() + k] = 0;
    for (int c = 0; c < 3; ++c) {
        atomicMin(selfInts[c], int(orderedBits(step[c]) ^ 0x80000000u));
        atomicMax(selfInts[3 + c], int(orderedBits(step[c]) ^ 0x80000000u));
    }
}
