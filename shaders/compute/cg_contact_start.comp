// implicit_euler with contacts in the solve (docs/integrators.md, "Contact in the solve"): the
// solve's first guess Δv₀ = S Δv + the fixed part, from the last step's solution Δv, or from 0
// where that was no better (cg.fromZero), and the contact's fixed velocity change (z n, and a
// held contact's hold). cg_warm_start.comp
// then forms A Δv₀ and |S (b − A Δv₀)|².
#include "layout.glsl"
#include "common.glsl"
#include "solve_contact.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;
    uint k = vertexIndex(ij);
    // 0 on pinned rows, whose Δv is 0
    vec3 dv = cg.fromZero != 0u ? vec3(0.0) : cgVelocityChange[k].xyz;
    cgVelocityChange[k] = vec4(filterContact(k, dv) + fixedChange(k), 0.0);
}
