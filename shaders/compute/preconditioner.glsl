// implicit_euler's preconditioner z = M⁻¹ r (docs/integrators.md, "Preconditioners"): r itself,
// or with PRECONDITIONER_JACOBI the inverted 3×3 diagonal block of A at the vertex, or with
// PRECONDITIONER_MULTIGRID the V-cycle's z, which cg_preconditioned.comp left in cgProduct
// (filtered there); with contacts in the solve S M⁻¹ r (solve_contact.glsl).
#include "solve_contact.glsl"
vec3 precondition(uint k, vec3 r) {
#ifdef PRECONDITIONER_JACOBI
    vec3 d = cgInverse[2u * k].xyz, o = cgInverse[2u * k + 1u].xyz;  // (xx, yy, zz), (xy, xz, yz)
    return filterContact(k, vec3(d.x * r.x + o.x * r.y + o.y * r.z,
                                 o.x * r.x + d.y * r.y + o.z * r.z,
                                 o.y * r.x + o.z * r.y + d.z * r.z));
#endif
#ifdef PRECONDITIONER_MULTIGRID
    return cgProduct[k].xyz;
#endif
    return r;
}
