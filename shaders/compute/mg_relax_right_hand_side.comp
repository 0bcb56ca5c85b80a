// implicit_euler's multigrid preconditioner, line Gauss–Seidel's first half on level
// lineLevel() (multigrid.glsl; src/cpu/cpu_multigrid.cpp lineRightHandSide): for every vertex on
// the lines of colour lineColour() in lineDirection(), r − (A z − A_line z_line), the stencil's
// blocks off the line times z on other colours' lines, into t (free while the grid is smoothed).
// One invocation per vertex: x along the line, y the colour's lines; mg_relax.comp then solves
// each line.
#include "layout.glsl"
#include "common.glsl"
#include "multigrid.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

void main() {
    if (cg.done != 0u) return;
    int l = lineLevel(), nu = levelU(l), nv = levelV(l), direction = lineDirection();
    int line = lineColour() + 5 * int(gl_GlobalInvocationID.y), a = int(gl_GlobalInvocationID.x);
    if (line >= (direction == 0 ? nv : nu) || a >= lineLength(l, direction)) return;
    ivec2 ij = onLine(direction, line, a);
    int k = ij.y * nu + ij.x;
    storeVector(l, k, kMgT, residualAt(l, ij, k, direction));
}
