// Self-collision's hash, the prefix sum's second level: one work group scans the block sums
// (inclusive), 256 at a time with the carry of those before.
#include "layout.glsl"
#include "common.glsl"
#include "self_contact.glsl"

layout(local_size_x = 256) in;

shared int scan[256];

void main() {
    uint l = gl_LocalInvocationID.x;
    uint blocks = (selfBuckets() + 1u + kScanBlock - 1u) / kScanBlock;
    int carry = 0;
    for (uint base = 0u; base < blocks; base += kScanBlock) {
        uint i = base + l;
        scan[l] = i < blocks ? selfInts[selfBlockSums() + i] : 0;
        barrier();
        for (uint d = 1u; d < kScanBlock; d *= 2u) {
            int add = l >= d ? scan[l - d] : 0;
            barrier();
            scan[l] += add;
            barrier();
        }
        if (i < blocks) selfInts[selfBlockSums() + i] = scan[l] + carry;
        carry += scan[kScanBlock - 1u];
        barrier();
    }
}
