// The first level of the conjugate gradient's dot products (docs/integrators.md): each work
// group sums its invocations' values in shared memory and stores one partial sum; cg_reduce.comp
// sums the partials. Included after the kernel's local_size layout, which sizes the array.
// Call from uniform control flow (every invocation of the group, in the grid or not).

shared float groupSums[gl_WorkGroupSize.x * gl_WorkGroupSize.y];

// Σ value over the work group, in invocation 0 (a tree in shared memory; any group size).
float workGroupSum(float value) {
    uint t = gl_LocalInvocationIndex;
    uint n = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
    groupSums[t] = value;
    memoryBarrierShared();
    barrier();
    uint stride = 1u;
    while (2u * stride < n) stride *= 2u;
    for (; stride > 0u; stride >>= 1) {
        if (t < stride && t + stride < n) groupSums[t] += groupSums[t + stride];
        memoryBarrierShared();
        barrier();
    }
    return groupSums[0];
}

#ifdef INTEGRATOR_IMPLICIT_EULER
// The work group's Σ value into its slot of cgPartials.
void storeGroupSum(float value) {
    float sum = workGroupSum(value);
    if (gl_LocalInvocationIndex == 0u)
        cgPartials[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = sum;
}

// Two sums: the first in the group's slot, the second as many slots further on.
void storeGroupSums(float first, float second) {
    storeGroupSum(first);
    barrier();  // groupSums is reused
    float sum = workGroupSum(second);
    if (gl_LocalInvocationIndex == 0u)
        cgPartials[gl_NumWorkGroups.x * gl_NumWorkGroups.y + gl_WorkGroupID.y * gl_NumWorkGroups.x +
                   gl_WorkGroupID.x] = sum;
}
#endif
