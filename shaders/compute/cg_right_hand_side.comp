// implicit_euler, after the forces pass (docs/integrators.md): the right-hand side
// b = h (F(x_n) + m_k (g − c v_n) − h H v_n) of (m_k (1 + hc) I + h² H) Δv = b, and the conjugate
// gradient's start Δv = 0, r = b, p = r, with the work groups' partial sums of r·r.
// Pinned rows are 0.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR velocities
#include "stiffness.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float rr = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {  // no early return: every invocation sums below
        uint k = vertexIndex(ij);
        vec4 x = positions[k];
        vec3 v = velocities[k].xyz;
        vec3 hv = stiffnessProduct(ij, k);
        if (grabbed(k)) hv += uGrab.w * v;
        float h = params.dt;
        vec3 b = vec3(0.0);  // a pinned row (x.w = 0)
        if (x.w != 0.0) {
            float m = 1.0 / x.w;  // m_k [kg]
            b = h * (forces[k].xyz + m * (params.gravity - params.dampingRate * v) - h * hv);
        }
        cgVelocityChange[k] = vec4(0.0);
        cgResidual[k] = vec4(b, 0.0);
        cgDirection[k] = vec4(b, 0.0);
        rr = dot(b, b);
    }
    storeGroupSum(rr);
}
