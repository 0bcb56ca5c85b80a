// Self-collision, an iteration's start (cpu_self_collision.cpp buildCells): each owner's box
// grown by h/2, the longest owned edge into the header, the hash's buckets emptied.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k == 0u) {
        selfInts[7] = 0;           // the iteration's contacts
        selfInts[8] = 2147483647;  // no crowded vertex yet
    }
    for (uint b = 4u * k; b < 4u * k + 4u; ++b) {  // B + 1 ≤ 4N
        if (b <= selfBuckets()) selfInts[selfStarts() + b] = 0;
        if (b < selfBuckets()) selfInts[selfCursors() + b] = 0;
    }
    if (k >= selfCount()) return;
    ivec2 ij = ivec2(int(k % uint(gridU())), int(k / uint(gridU())));
    vec3 y = selfVector(k, kSelfY), low = y, high = y;
    float longest = 0.0;
    for (int e = 0; e < 3; ++e) {
        ivec2 end = ij + kOwnedEdgeEnds[e];
        if (end.x >= gridU() || end.y >= gridV()) continue;
        vec3 c = selfVector(vertexIndex(end), kSelfY);
        longest = max(longest, dot(c - y, c - y));
        low = min(low, c);
        high = max(high, c);
    }
    setSelfVector(k, kSelfLow, low - vec3(0.5 * uThickness));
    setSelfVector(k, kSelfHigh, high + vec3(0.5 * uThickness));
    atomicMax(selfInts[6], floatBitsToInt(longest));  // non-negative floats order as ints
}
