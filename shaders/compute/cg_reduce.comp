// The second level of the conjugate gradient's dot products (docs/integrators.md): one work
// group sums the partial sums the previous pass stored and turns the total into the solve's
// next scalar, in cg, which the following passes read: no host round trip per kernel.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = 256) in;

#include "reduction.glsl"

// Which sum this is (gpu::CgReduction): b·b at the start, p·A p (→ α), or the new r·r (→ β).
layout(location = 0) uniform int uReduction;
const int kStart = 0, kAlpha = 1, kBeta = 2;
const uint kRunning = 0u, kConverged = 1u, kStopped = 2u;

// The grid dispatch's work groups, one partial sum each.
uint partialCount() {
    return uint((gridU() + WX - 1) / WX) * uint((gridV() + WY - 1) / WY);
}

// Stop when |r| ≤ tolerance·|b| (b = 0 included); a non-finite r·r stops the solve too.
uint judge(float rr) {
    float tolerance = params.cgTolerance;
    float goal = tolerance * tolerance * cg.bb;
    if (rr <= goal) return kConverged;
    return rr > goal ? kRunning : kStopped;
}

void main() {
    if (uReduction != kStart && cg.done != kRunning) return;
    float sum = 0.0;
    for (uint g = gl_LocalInvocationIndex; g < partialCount(); g += gl_WorkGroupSize.x)
        sum += cgPartials[g];
    sum = workGroupSum(sum);
    if (gl_LocalInvocationIndex != 0u) return;
    if (uReduction == kStart) {
        cg.rr = sum;
        cg.bb = sum;
        cg.iterations = 0u;
        cg.done = judge(sum);
    } else if (uReduction == kAlpha) {
        // A is positive definite: only a non-finite state gets p·A p ≤ 0 (or NaN).
        if (sum > 0.0) cg.alpha = cg.rr / sum;
        else cg.done = kStopped;
    } else {
        cg.beta = sum / cg.rr;
        cg.rr = sum;
        cg.iterations += 1u;
        cg.done = judge(sum);
    }
}
