// Self-collision's hash, the scatter: each vertex into its bucket's next slot. The order inside
// a bucket does not matter: the corrections are summed in fixed point.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k >= selfCount()) return;
    uint bucket = uint(selfInts[selfCells() + 4u * k + 3u]);
    int slot = atomicAdd(selfInts[selfCursors() + bucket], 1);
    selfInts[selfSorted() + uint(selfInts[selfStarts() + bucket] + slot)] = int(k);
}
