// Self-collision's hash, the count (cpu_self_collision.cpp buildCells): each vertex's cell at
// size h + 2L and its bucket; the bucket's count at starts[bucket + 1].
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint k = selfInvocation();
    if (k >= selfCount()) return;
    float cell = uThickness + 2.0 * sqrt(intBitsToFloat(selfInts[6]));
    vec3 c = floor(selfVector(k, kSelfY) / cell);
    // A non-finite position lands in cell 0; the step's instability check reports it.
    ivec3 home = all(lessThan(abs(c), vec3(1e9))) ? ivec3(c) : ivec3(0);
    uint bucket = hashCell(home);
    uint at = selfCells() + 4u * k;
    selfInts[at] = home.x;
    selfInts[at + 1u] = home.y;
    selfInts[at + 2u] = home.z;
    selfInts[at + 3u] = int(bucket);
    atomicAdd(selfInts[selfStarts() + bucket + 1u], 1);
}
