// Many steps in one dispatch, for small cloths whose steps cost more in dispatches than in work
// (docs/performance.md; explicit_euler and symplectic_euler). One work group holds the whole grid,
// each invocation a strided set of vertices, and runs uStepCount steps: pass 1 (forces.glsl) for
// all vertices, a barrier, pass 2 (euler_step.glsl), a barrier. The physics are the per-pass
// kernels' own functions; the buffers are coherent so that the group sees its own writes.
#define STATE_COHERENT coherent
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#include "grab.glsl"
#include "step_end.glsl"
#include "euler_step.glsl"

layout(local_size_x = MANY_STEPS_GROUP) in;

layout(location = 3) uniform uint uStepCount;  // steps of this dispatch: uStep, uStep + 1, ...

vec3 positionAt(ivec2 q) { return positions[vertexIndex(q)].xyz; }
#include "forces.glsl"

// Both phases end on a buffer barrier and barrier(): every write of the phase is visible to the
// whole group before the next phase reads it (pass 2 writes positions pass 1 gathers, and the
// status that freezes the state). The loops' bounds are uniform, so every invocation reaches
// every barrier.
void main() {
    uint count = uint(gridU()) * uint(gridV());
    uint stride = gl_WorkGroupSize.x;
    for (uint s = 0u; s < uStepCount; ++s) {
        uint step = uStep + s;
        for (uint k = gl_LocalInvocationIndex; k < count; k += stride)
            storeForce(ivec2(int(k % uint(gridU())), int(k / uint(gridU()))));
        memoryBarrierBuffer();
        barrier();
        if (!frozen(step))
            for (uint k = gl_LocalInvocationIndex; k < count; k += stride)
                integrateVertex(step, k);
        memoryBarrierBuffer();
        barrier();
    }
}
