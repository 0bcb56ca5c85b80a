// implicit_euler's conjugate gradient, its start (docs/integrators.md): from the warm start
// r = b − A Δv₀, or, where that was no better a guess (cg.fromZero), from Δv = 0 with r = b;
// then z = M⁻¹ r, p = z and the work groups' partial sums of r·z. With contacts in the solve
// cg_contact_start.comp chose Δv₀ and the product is A Δv₀ either way: r = S (b − A Δv₀).
#include "layout.glsl"
#include "common.glsl"
#include "preconditioner.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float rz = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        vec3 r = cgResidual[k].xyz;  // b
#ifdef HAS_SOLVE_CONTACTS
        r = filterContact(k, filterContact(k, r) - cgProduct[k].xyz);
#else
        if (cg.fromZero != 0u)
            cgVelocityChange[k] = vec4(0.0);
        else
            r -= cgProduct[k].xyz;
#endif
        cgResidual[k] = vec4(r, 0.0);
#ifndef PRECONDITIONER_MULTIGRID  // p and r·z follow the V-cycle (cg_preconditioned.comp)
        vec3 z = precondition(k, r);
        cgDirection[k] = vec4(z, 0.0);
        rz = dot(r, z);
#endif
    }
#ifndef PRECONDITIONER_MULTIGRID
    storeGroupSum(rz);
#endif
}
