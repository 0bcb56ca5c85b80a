// implicit_euler's conjugate gradient with the multigrid preconditioner (docs/integrators.md):
// after the V-cycle, z = M⁻¹ r (the fine grid's z in double, multigrid.glsl) into cgProduct, the
// product being spent, and the work groups' partial sums of r·r and r·z; at the solve's start
// (uStart) p = z and r·z alone.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"
#include "solve_contact.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

layout(location = 6) uniform int uStart;

void main() {
    if (cg.done != 0u) return;
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float rr = 0.0, rz = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        vec3 r = cgResidual[k].xyz, z = filterContact(k, vec3(loadVector(0, int(k), kMgZ)));
        if (uStart != 0) cgDirection[k] = vec4(z, 0.0);
        else cgProduct[k] = vec4(z, 0.0);
        rr = dot(r, r);
        rz = dot(r, z);
    }
    if (uStart != 0) storeGroupSum(rz);
    else storeGroupSums(rr, rz);
}
