// Self-collision's hash, the prefix sum's last step: each block adds the sum of the blocks
// before it.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

void main() {
    uint i = selfInvocation();
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (i > selfBuckets() || block == 0u) return;
    selfInts[selfStarts() + i] += selfInts[selfBlockSums() + block - 1u];
}
