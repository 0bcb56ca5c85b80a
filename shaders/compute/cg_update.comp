// implicit_euler's conjugate gradient: Δv += α p, r −= α A p, and the work groups' partial sums
// of the new r·r and r·z, z = M⁻¹ r (docs/integrators.md); with contacts in the solve r stays
// filtered (solve_contact.glsl, through preconditioner.glsl).
#include "layout.glsl"
#include "common.glsl"
#include "preconditioner.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    if (cg.done != 0u) return;
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float rr = 0.0, rz = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        float alpha = cg.alpha;
        cgVelocityChange[k].xyz += alpha * cgDirection[k].xyz;
        vec3 r = filterContact(k, cgResidual[k].xyz - alpha * cgProduct[k].xyz);
        cgResidual[k] = vec4(r, 0.0);
        rr = dot(r, r);
#ifndef PRECONDITIONER_MULTIGRID
        rz = dot(r, precondition(k, r));
#endif
    }
#ifndef PRECONDITIONER_MULTIGRID  // the sums follow the V-cycle (cg_preconditioned.comp)
    storeGroupSums(rr, rz);
#endif
}
