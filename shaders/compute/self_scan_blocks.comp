// Self-collision's hash, the prefix sum's first level: each work group scans its 256 of the
// B + 1 bucket counts in shared memory (inclusive; starts[0] = 0, so starts[b] becomes the
// vertices of the buckets before b) and leaves its total in the block sums.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

shared int scan[256];

void main() {
    uint i = selfInvocation(), l = gl_LocalInvocationID.x;
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    bool inside = i <= selfBuckets();
    scan[l] = inside ? selfInts[selfStarts() + i] : 0;
    barrier();
    for (uint d = 1u; d < kScanBlock; d *= 2u) {  // Hillis and Steele
        int add = l >= d ? scan[l - d] : 0;
        barrier();
        scan[l] += add;
        barrier();
    }
    if (inside) selfInts[selfStarts() + i] = scan[l];
    if (l == kScanBlock - 1u) selfInts[selfBlockSums() + block] = scan[l];
}
