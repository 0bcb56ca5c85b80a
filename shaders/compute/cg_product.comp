// implicit_euler's conjugate gradient, one iteration's matrix-vector product (docs/integrators.md):
// A p = m_k (1 + hc) p + h² H p (+ h D p with spring damping, D = −∂F/∂v), a gather over the
// stencil at x_n (no atomics), plus the grab's h² K p, and the work groups' partial sums of p·A p.
// Pinned rows are 0.
#include "layout.glsl"
#include "common.glsl"
#include "grab.glsl"
#define STIFFNESS_VECTOR cgDirection
#include "stiffness.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#include "reduction.glsl"

void main() {
    if (cg.done != 0u) return;  // the same for the whole dispatch: converged or stopped
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    float pAp = 0.0;
    if (ij.x < gridU() && ij.y < gridV()) {
        uint k = vertexIndex(ij);
        float inverseMass = positions[k].w;
        vec3 p = cgDirection[k].xyz;
        vec3 ap = vec3(0.0);
        if (inverseMass != 0.0) {
            float h = params.dt, h2 = h * h;
            float drag = 1.0 + h * params.dampingRate;
            // h² H p + h D p in one gather: h² (H p + D p / h).
            ap = (drag / inverseMass) * p + h2 * stiffnessProduct(ij, k, 1.0 / h);
            if (grabbed(k)) ap += h2 * uGrab.w * p;
        }
        cgProduct[k] = vec4(ap, 0.0);
        pAp = dot(p, ap);
    }
    storeGroupSum(pAp);
}
