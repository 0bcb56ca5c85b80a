// Pass 1 (DESIGN.md §3): one invocation per vertex gathers the springs of its up to 12
// neighbours (no atomics), adds the wind and the grab, and writes its force and normal.
#include "layout.glsl"
#include "common.glsl"
#include "springs.glsl"
#include "grab.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

vec3 positionAt(int i, int j) { return positions[vertexIndex(ivec2(i, j))].xyz; }

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;  // grids need not fill the work groups
    uint k = vertexIndex(ij);
    vec3 p = positions[k].xyz;
    vec3 f = vec3(0.0);
#if NUM_SPRING_OFFSETS > 0
    // One loop walks every family the scene declares (the seed's Q10).
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        f += springForce(p, positions[vertexIndex(q)].xyz, springStiffness(s),
                         springRestLength(s));
    }
#endif
    int i = ij.x, j = ij.y;
    vec3 n = vertexNormal(positionAt(min(i + 1, gridU() - 1), j), positionAt(max(i - 1, 0), j),
                          positionAt(i, min(j + 1, gridV() - 1)), positionAt(i, max(j - 1, 0)));
#ifdef HAS_WIND
    f += windForce(n, params.wind.xyz, params.wind.w);
#endif
    if (grabbed(k)) f += grabForce(p, uGrab.xyz, uGrab.w);
    forces[k] = vec4(f, 0.0);
    normals[k] = vec4(n, 0.0);
}
