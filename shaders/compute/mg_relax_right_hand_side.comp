// implicit_euler's multigrid preconditioner, line Gauss–Seidel's first half on level uLevel
// (multigrid.glsl; src/cpu/cpu_multigrid.cpp relaxLine): for every vertex on the lines of colour
// uLine.y in direction uLine.x, r − (A z − A_line z_line), the stencil's blocks off the line
// times z on other colours' lines, into t (free while the grid is smoothed). One invocation per
// vertex: x along the line, y the colour's lines; mg_relax.comp then solves each line.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = uLevel, nu = levelU(l), nv = levelV(l), direction = uLine.x;
    int line = uLine.y + 5 * int(gl_GlobalInvocationID.y), a = int(gl_GlobalInvocationID.x);
    if (line >= (direction == 0 ? nv : nu) || a >= lineLength(l, direction)) return;
    ivec2 ij = onLine(direction, line, a);
    int k = ij.y * nu + ij.x;
    dvec3 sum = dvec3(0.0lf);
    if (!pinnedAt(l, ij)) {
        sum = loadVector(l, k, kMgR);
        for (int dj = max(-2, -ij.y); dj <= min(2, nv - 1 - ij.y); ++dj)
            for (int di = max(-2, -ij.x); di <= min(2, nu - 1 - ij.x); ++di) {
                if (direction == 0 ? dj == 0 : di == 0) continue;  // on the line
                sum -= times(loadBlock(blockAt(l, k, stencilSlot(di, dj))),
                             loadVector(l, k + dj * nu + di, kMgZ));
            }
    }
    storeVector(l, k, kMgT, sum);
}
