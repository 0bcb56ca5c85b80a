// implicit_euler's conjugate gradient, one iteration's matrix-vector product A p (system.glsl)
// and the work groups' partial sums of p·A p (docs/integrators.md). Pinned rows are 0.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR cgDirection
#include "stiffness.glsl"
#include "system.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    if (cg.done != 0u) return;  // the same for the whole dispatch: converged or stopped
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float pAp = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        vec3 ap = systemProduct(ij, k);
        cgProduct[k] = vec4(ap, 0.0);
        pAp = dot(cgDirection[k].xyz, ap);
    }
    storeGroupSum(pAp);
}
