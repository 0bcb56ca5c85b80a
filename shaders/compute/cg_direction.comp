// implicit_euler's conjugate gradient: the next search direction p = z + β p, z = M⁻¹ r
// (docs/integrators.md). Its own pass: the next product gathers p from the neighbours.
#include "layout.glsl"
#include "common.glsl"
#include "preconditioner.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;
    uint k = vertexIndex(ij);
    // Filtered again with contacts in the solve (src/cpu/cpu_implicit.cpp says why).
    cgDirection[k].xyz =
        filterContact(k, precondition(k, cgResidual[k].xyz) + cg.beta * cgDirection[k].xyz);
}
