// Pass 1 (DESIGN.md §3): one invocation per vertex gathers the springs of its up to 12
// neighbours (no atomics), adds the wind and writes its force and normal.
#include "layout.glsl"
#include "common.glsl"

layout(local_size_x = WX, local_size_y = WY) in;

#if NUM_SPRING_OFFSETS > 0
// The active rows of kSpringOffsets (src/core/grid.h), generated from that table by the host:
// (di, dj, family, slot). One loop walks every family the scene declares (the seed's Q10).
const ivec4 kSpringOffsets[NUM_SPRING_OFFSETS] = ivec4[](SPRING_OFFSETS);
#endif

// The viewer's grab (Solver::setGrab): a spring F = K (target − x) on one vertex, part of F
// like any other force. uGrabVertex = -1 when nothing is grabbed: one compare per vertex.
layout(location = 0) uniform int uGrabVertex;
layout(location = 1) uniform vec4 uGrab;  // xyz target [m], w stiffness K [N/m]

vec3 positionAt(int i, int j) { return positions[vertexIndex(ivec2(i, j))].xyz; }

void main() {
    ivec2 ij = ivec2(gl_GlobalInvocationID.xy);
    if (ij.x >= gridU() || ij.y >= gridV()) return;  // grids need not fill the work groups
    uint k = vertexIndex(ij);
    vec3 p = positions[k].xyz;
    vec3 f = vec3(0.0);
#if NUM_SPRING_OFFSETS > 0
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        f += springForce(p, positions[vertexIndex(q)].xyz, params.stiffness[s.z],
                         params.restLength[s.w / 4][s.w % 4]);
    }
#endif
    int i = ij.x, j = ij.y;
    vec3 n = vertexNormal(positionAt(min(i + 1, gridU() - 1), j), positionAt(max(i - 1, 0), j),
                          positionAt(i, min(j + 1, gridV() - 1)), positionAt(i, max(j - 1, 0)));
#ifdef HAS_WIND
    f += windForce(n, params.wind.xyz, params.wind.w);
#endif
    if (int(k) == uGrabVertex) f += grabForce(p, uGrab.xyz, uGrab.w);
    forces[k] = vec4(f, 0.0);
    normals[k] = vec4(n, 0.0);
}
