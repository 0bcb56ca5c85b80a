// implicit_euler's warm start (docs/integrators.md): A Δv₀ with Δv₀ the last step's solution
// (held 0 on pinned rows by the right-hand side's pass), into cgProduct, and the work groups'
// partial sums of |b − A Δv₀|², b in cgResidual (with contacts in the solve, S (b − A Δv₀)). With
// contacts it runs a second time on the Δv₀ cg_contact_start.comp wrote.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR cgVelocityChange
#include "stiffness.glsl"
#include "system.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float rr = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        vec3 ap = systemProduct(ij, k);
        cgProduct[k] = vec4(ap, 0.0);
        vec3 r = filterContact(k, cgResidual[k].xyz) - ap;
        rr = dot(r, r);
    }
    storeGroupSum(rr);
}
