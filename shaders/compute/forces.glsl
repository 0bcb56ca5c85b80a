// The force pass's physics for one vertex (DESIGN.md §2, §3), shared by forces.comp and
// many_steps.comp. The including kernel first defines `vec3 positionAt(ivec2 q)` for any q inside
// the grid within two of the vertex: where the positions come from (the SSBO, or the work
// group's tile in shared memory, forces_tile.glsl).

#ifdef HAS_BENDING
#define BENDING_FIELD(q) positionAt(q)
#include "bending.glsl"
#endif

#ifdef HAS_WIND
// K_w at vertex ij [N]: with HAS_BORDER_SHARES (a material) Params holds the pressure times a
// cell's area, and a vertex on a border presses with its share of it (src/model/scene.h
// windArea): half on an edge, a quarter at a corner.
float windStrengthAt(ivec2 ij) {
    float s = params.windStrength;
#ifdef HAS_BORDER_SHARES
    if (ij.x == 0 || ij.x == gridU() - 1) s *= 0.5;
    if (ij.y == 0 || ij.y == gridV() - 1) s *= 0.5;
#endif
    return s;
}
#endif

// The springs of the up to 12 neighbours, a material's bending, the damping along the springs,
// the wind and the grab on vertex ij
// (index k), and its normal.
void gatherForces(ivec2 ij, uint k, out vec3 f, out vec3 n) {
    vec3 p = positionAt(ij);
    f = vec3(0.0);
#if NUM_SPRING_OFFSETS > 0
    // One loop walks every family the scene declares (the seed's Q10).
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        f += springForce(p, positionAt(q), springStiffnessAt(s, ij), springRestLength(s));
    }
#endif
#ifdef HAS_BENDING
    f += bendingForce(ij, params.bending.xyz);
#endif
#ifdef HAS_SPRING_DAMPING
    // After the bending, spring by spring, as the CPU (cpu_forces.cpp); the velocities come
    // straight from the SSBO (no pass writes them while the forces are gathered).
    vec3 vk = velocities[k].xyz;
    for (int o = 0; o < NUM_SPRING_OFFSETS; ++o) {
        ivec4 s = kSpringOffsets[o];
        ivec2 q = ij + s.xy;
        if (!insideGrid(q)) continue;
        f += springDampingForce(positionAt(q) - p, velocities[vertexIndex(q)].xyz - vk,
                                springDampingAt(s, ij), springRestLength(s));
    }
#endif
    int i = ij.x, j = ij.y;
    n = vertexNormal(positionAt(ivec2(min(i + 1, gridU() - 1), j)),
                     positionAt(ivec2(max(i - 1, 0), j)),
                     positionAt(ivec2(i, min(j + 1, gridV() - 1))),
                     positionAt(ivec2(i, max(j - 1, 0))));
#ifdef HAS_WIND
    f += windForce(n, params.windDirection, windStrengthAt(ij));
#endif
    if (grabbed(k)) f += grabForce(p, uGrab.xyz, uGrab.w);
}

// Pass 1's output for vertex ij: its force and normal, as vec4 stores.
void storeForce(ivec2 ij) {
    uint k = vertexIndex(ij);
    vec3 f, n;
    gatherForces(ij, k, f, n);
    forces[k] = vec4(f, 0.0);
    normals[k] = vec4(n, 0.0);
}
