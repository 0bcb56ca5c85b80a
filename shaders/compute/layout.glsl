// Storage blocks shared by the compute passes (DESIGN.md §3). Mirrored in src/gpu/gpu_layout.h,
// whose static_asserts pin the offsets: change both together.
// One vec4 per vertex, index k = j·nu + i (DESIGN.md §2).

layout(std430, binding = 0) buffer Positions {
    vec4 positions[];  // xyz [m], w inverse mass [1/kg], 0 for a pinned vertex
};
layout(std430, binding = 1) buffer Velocities {
    vec4 velocities[];  // xyz [m/s], w the pinned vertex's slot in pins[]
};
layout(std430, binding = 2) buffer Forces {
    vec4 forces[];  // spring + wind force [N] of the current step
};
layout(std430, binding = 3) buffer Normals {
    vec4 normals[];  // unit vertex normal, 0 where undefined; the renderer draws with it
};
layout(std430, binding = 4) readonly buffer Params {
    ivec4 grid;           // nu, nv
    vec4 stiffness;       // K structural, shear, bend [N/m]
    vec4 restLength[3];   // L of spring-table slot o at [o / 4][o % 4] [m]
    vec4 gravity;         // xyz g [m/s²], w damping μ [N·s/m]
    vec4 wind;            // xyz unit direction, w strength K_w [N]
    vec4 integration;     // x Δt [s], y max_speed² [m²/s²]
} params;

#ifdef HAS_COLLIDERS
// Plane n: colliders[2n] = point, colliders[2n + 1] = unit normal.
// Sphere n: colliders[2 NUM_PLANES + n] = (centre, radius). Applied in COLLIDERS_IN_SCENE_ORDER.
layout(std430, binding = 5) readonly buffer Colliders {
    vec4 colliders[];
};
#endif

// Always present: the viewer pins and releases vertices at run time (Solver::setPinned).
layout(std430, binding = 6) readonly buffer Pins {
    vec4 pins[];  // xyz pinned position [m]
};

int gridU() { return params.grid.x; }
int gridV() { return params.grid.y; }

bool insideGrid(ivec2 ij) {
    return ij.x >= 0 && ij.y >= 0 && ij.x < gridU() && ij.y < gridV();
}

uint vertexIndex(ivec2 ij) { return uint(ij.y) * uint(gridU()) + uint(ij.x); }
