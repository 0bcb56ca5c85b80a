// The step control's measure on the GPU (src/solver/step_check.h, src/gpu/gpu_step_check.cpp):
// how much the step grew the stretch max(0, (|d| − L)/L) of each structural spring since the
// kept start, each invocation a vertex's springs along +u and +v, and the work group's largest
// growth into its slot after the kept state. +inf where a length is not finite. The host's twin
// is largestStretchGrowth (src/solver/diagnostics.cpp), in double.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

layout(std430, binding = 18) buffer StepStart {
    vec4 stepStart[];  // the kept positions, the kept velocities (n each), the groups' maxima
};

// The group's largest growth, at least 0, as bits: a non-negative float's bits order as it does.
shared uint groupMax;

// The growth of the spring from ij to ij + offset, of rest length restLength [m].
float growth(ivec2 ij, ivec2 offset, float restLength) {
    if (!insideGrid(ij + offset)) return 0.0;
    uint a = vertexIndex(ij), b = vertexIndex(ij + offset);
    vec3 before = stepStart[b].xyz - stepStart[a].xyz, now = positions[b].xyz - positions[a].xyz;
    // Tested on the bits (common.glsl), before max(), which may return its other operand for NaN.
    if (nonFinite(before) || nonFinite(now)) return uintBitsToFloat(0x7f800000u);  // +inf
    return (max(length(now), restLength) - max(length(before), restLength)) / restLength;
}

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float g = 0.0;
    // Spring-table slots 0 and 2: (1, 0) and (0, 1) (src/model/grid.h kSpringOffsets).
    if (insideGrid(ij))
        g = max(growth(ij, ivec2(1, 0), params.restLength[0][0]),
                growth(ij, ivec2(0, 1), params.restLength[0][2]));
    uint t = gl_LocalInvocationIndex;
    if (t == 0u) groupMax = 0u;
    memoryBarrierShared();
    barrier();
    atomicMax(groupMax, floatBitsToUint(max(g, 0.0)));
    memoryBarrierShared();
    barrier();
    if (t == 0u) {
        uint vertices = uint(gridU()) * uint(gridV());
        uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        stepStart[2u * vertices + group] = vec4(uintBitsToFloat(groupMax), 0.0, 0.0, 0.0);
    }
}
