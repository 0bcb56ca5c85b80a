// The second level of the conjugate gradient's dot products (docs/integrators.md): one work
// group sums the partial sums the previous pass stored and turns the total into the solve's
// next scalar, in cg, which the following passes read: no host round trip per kernel.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = 256) in;

#include "reduction.glsl"

// Which sum this is (gpu::CgReduction): b·b and s·s at the start, |b − A Δv₀|² of the warm start, r·z of
// the start, p·A p (→ α), or the new r·r and r·z (→ β, two sums).
layout(location = 0) uniform int uReduction;
const int kStart = 0, kAlpha = 1, kBeta = 2, kWarm = 3, kStartDirection = 4, kContactStart = 5;
const uint kRunning = 0u, kConverged = 1u, kStopped = 2u;

// The grid dispatch's work groups, one partial sum each (per sum).
uint partialCount() {
    return uint((gridU() + WX - 1) / WX) * uint((gridV() + WY - 1) / WY);
}

// Stop when |r| ≤ tolerance·|b| (b = 0 included) or |r| ≤ ε |s|, the rounding of b's terms
// (src/cpu/cpu_implicit.cpp); a non-finite r·r stops the solve too.
uint judge(float rr) {
    float tolerance = params.cgTolerance;
    float goal = max(tolerance * tolerance * cg.bb, cg.floor);
    if (rr <= goal) return kConverged;
    return rr > goal ? kRunning : kStopped;
}

// Σ of sum `which` (0 or 1) over the partials, in invocation 0.
float total(uint which) {
    float sum = 0.0;
    uint groups = partialCount();
    for (uint g = gl_LocalInvocationIndex; g < groups; g += gl_WorkGroupSize.x)
        sum += cgPartials[which * groups + g];
    return workGroupSum(sum);
}

void main() {
    bool starting = uReduction == kStart || uReduction == kWarm ||
                    uReduction == kStartDirection || uReduction == kContactStart;
    if (!starting && cg.done != kRunning) return;
    float sum = total(0u);
    float second = 0.0;
    if (uReduction == kBeta || uReduction == kStart) {
        barrier();  // groupSums is reused
        second = total(1u);
    }
    if (gl_LocalInvocationIndex != 0u) return;
    if (uReduction == kStart) {
        cg.bb = sum;
        const float roundoff = 5.9604645e-8;  // 2⁻²⁴, float's unit roundoff
        cg.floor = roundoff * roundoff * second;
        cg.iterations = 0u;
        cg.done = kRunning;
    } else if (uReduction == kWarm) {
        // The last solution is kept only where it beats Δv = 0 (docs/integrators.md).
        cg.fromZero = sum < cg.bb ? 0u : 1u;
        cg.rr = sum < cg.bb ? sum : cg.bb;
    } else if (uReduction == kContactStart) {
        // |S (b − A Δv₀)|² of the first guess with the contacts' z n; the stopping test is
        // relative to it where it exceeds |b| (src/cpu/cpu_implicit.cpp).
        cg.rr = sum;
        cg.bb = max(cg.bb, sum);
    } else if (uReduction == kStartDirection) {
        cg.rz = sum;
        cg.done = judge(cg.rr);
    } else if (uReduction == kAlpha) {
        // A is positive definite: only a non-finite state gets p·A p ≤ 0 (or NaN).
        if (sum > 0.0) cg.alpha = cg.rz / sum;
        else cg.done = kStopped;
    } else {
        cg.rr = sum;
        cg.iterations += 1u;
        cg.done = judge(sum);
        cg.beta = second / cg.rz;
        cg.rz = second;
    }
}
