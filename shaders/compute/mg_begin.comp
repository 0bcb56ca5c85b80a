// implicit_euler's multigrid preconditioner: the V-cycle's start on the fine grid, r the
// conjugate gradient's residual in double and z = 0 (multigrid.glsl).
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    ivec2 ij;
    int k;
    if (!levelVertex(0, ij, k)) return;
    storeVector(0, k, kMgR, dvec3(cgResidual[k].xyz));
    storeVector(0, k, kMgZ, dvec3(0.0lf));
}
