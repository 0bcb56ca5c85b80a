// Pass 1 (DESIGN.md §3): one invocation per vertex gathers the springs of its up to 12
// neighbours (no atomics), adds the wind and the grab, and writes its force and normal. The
// positions come straight from the SSBO, or, with FORCES_TILED, from the work group's tile in
// shared memory (forces_tile.glsl); docs/performance.md measures both.
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#include "grab.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#ifdef FORCES_TILED
#include "forces_tile.glsl"
#else
vec3 positionAt(ivec2 q) { return positions[vertexIndex(q)].xyz; }
#endif
#include "forces.glsl"

void main() {
#ifdef FORCES_TILED
    loadTile();
#endif
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;  // grids need not fill the work groups
    storeForce(ij);
}
