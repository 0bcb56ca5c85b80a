// forces.comp's shared-memory tile (FORCES_TILED, docs/performance.md): the work group loads the
// positions of its WX × WY vertices and a 2-vertex halo (the bend springs' reach) once, as vec4
// loads, and the gather reads its 12 neighbours and the normal's 4 from shared memory instead of
// the SSBO. Same values, same arithmetic: the forces are bit for bit those of the plain pass.
// The host checks that the tile fits the device's shared memory.

const int kHalo = 2;
const int kTileU = WX + 2 * kHalo, kTileV = WY + 2 * kHalo;
shared vec4 tile[kTileU * kTileV];

// Grid coordinates of the tile's first cell.
ivec2 tileOrigin() { return ivec2(gl_WorkGroupID.xy) * ivec2(WX, WY) - ivec2(kHalo); }

// Every invocation of the group, before any returns (barrier() needs uniform control flow).
// Halo cells outside the grid stay unset: the gather skips neighbours outside the grid and the
// normal clamps to it, so they are never read.
void loadTile() {
    ivec2 origin = tileOrigin();
    for (int t = int(gl_LocalInvocationIndex); t < kTileU * kTileV; t += WX * WY) {
        ivec2 q = origin + ivec2(t % kTileU, t / kTileU);
        if (insideGrid(q)) tile[t] = positions[vertexIndex(q)];
    }
    memoryBarrierShared();
    barrier();
}

vec3 positionAt(ivec2 q) {
    ivec2 t = q - tileOrigin();
    return tile[t.y * kTileU + t.x].xyz;
}
