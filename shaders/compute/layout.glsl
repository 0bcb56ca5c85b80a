// The blocks shared by the compute passes (DESIGN.md §3): the scene's parameters as a uniform
// block, the state and tables as storage blocks. Mirrored in src/gpu/gpu_layout.h, whose
// static_asserts pin the offsets: change both together.
// One vec4 per vertex, index k = j·nu + i (DESIGN.md §2).

// many_steps.comp defines STATE_COHERENT as `coherent`: its invocations read what others of
// the same work group wrote in the same dispatch. The per-pass kernels need no such thing.
#ifndef STATE_COHERENT
#define STATE_COHERENT
#endif

layout(std430, binding = 0) STATE_COHERENT buffer Positions {
    vec4 positions[];  // xyz [m], w the vertex's inverse mass 1/m_k [1/kg], 0 for a pinned vertex
};
layout(std430, binding = 1) STATE_COHERENT buffer Velocities {
    vec4 velocities[];  // xyz [m/s], w the pinned vertex's slot in pins[]
};
layout(std430, binding = 2) STATE_COHERENT buffer Forces {
    vec4 forces[];  // spring + wind force [N] of the current step
};
layout(std430, binding = 3) STATE_COHERENT buffer Normals {
    vec4 normals[];  // unit vertex normal, 0 where undefined; the renderer draws with it
};
// The scene's parameters (gpu::Params), the same for every invocation: a uniform block, read
// through the uniform path rather than as storage. std140: each vec3 starts a 16-byte slot and the
// float after it fills the slot's last 4 bytes; an array of vec4 starts on 16 bytes.
layout(std140, binding = 0) uniform Params {
    ivec2 grid;             // nu, nv [vertices]
    float dt;               // Δt [s]
    float dampingRate;      // c [1/s]: the drag on vertex k is −c·m_k·v_k
    vec3 gravity;           // g [m/s²]
    float maxSpeedSquared;  // max_speed² [m²/s²]: a faster vertex makes the step unstable
    vec3 windDirection;     // unit; 0 without wind
    float windStrength;     // K_w [N] (a material's: K_w [N/m²] × du·dv); 0 without wind
    float cgTolerance;      // implicit_euler's relative CG tolerance on |r| / |b|
    // K [N/m] and L [m] of spring-table slot o at [o / 4][o % 4] (springStiffness,
    // springRestLength): std140 would pad a float[12] to 16 bytes per element; vec4s pack the
    // twelve as the C++ float[12]. A material's structural springs along u and v differ.
    vec4 stiffness[3];
    vec4 restLength[3];
    // w_u, w_v, t of a material's bending energy [N/m] (bending.glsl; read under HAS_BENDING).
    vec4 bending;
    // β [s] of the damping along the springs (springs.glsl; read under HAS_SPRING_DAMPING).
    float springDamping;
} params;

#ifdef HAS_COLLIDERS
// One record per collider in scene order, the meshes' SDF samples, the moving colliders' pose
// batch: src/gpu/gpu_collider_table.h lays it out, scene_colliders.glsl reads it.
layout(std430, binding = 5) readonly buffer Colliders {
    vec4 colliders[];
};
#endif

// Always present: the viewer pins and releases vertices at run time (Solver::setPinned).
layout(std430, binding = 6) readonly buffer Pins {
    vec4 pins[];  // xyz pinned position [m] (a follow pin: its rest position), w 0 or follow + 1
};

#ifdef INTEGRATOR_RK4
// RK4's stage state (docs/integrators.md): the start (x_n, v_n) of the step, w as in
// positions/velocities, and the running sums Σ = k1 + 2 k2 + 2 k3 of dx/dt and dv/dt.
layout(std430, binding = 8) buffer Rk4StartPositions {
    vec4 rk4StartPositions[];
};
layout(std430, binding = 9) buffer Rk4StartVelocities {
    vec4 rk4StartVelocities[];
};
layout(std430, binding = 10) buffer Rk4SumPositions {
    vec4 rk4SumPositions[];  // [m/s]
};
layout(std430, binding = 11) buffer Rk4SumVelocities {
    vec4 rk4SumVelocities[];  // [m/s²]
};
#endif

#ifdef INTEGRATOR_IMPLICIT_EULER
// implicit_euler's conjugate gradient on A Δv = b (docs/integrators.md), one vec4 per vertex;
// rows of pinned vertices stay 0.
layout(std430, binding = 8) buffer CgVelocityChange {
    vec4 cgVelocityChange[];  // the iterate Δv [m/s]
};
layout(std430, binding = 9) buffer CgResidual {
    vec4 cgResidual[];  // r = b − A Δv [N·s]
};
layout(std430, binding = 10) buffer CgDirection {
    vec4 cgDirection[];  // the search direction p [m/s]
};
layout(std430, binding = 11) buffer CgProduct {
    vec4 cgProduct[];  // A p [N·s]
};
// Partial sums per work group of the grid dispatch (gl_WorkGroupID.y · groupsX + .x): the first
// sum of a pass at [group], a second one (r·z beside r·r) at [groups + group].
layout(std430, binding = 12) buffer CgPartials {
    float cgPartials[];
};
// The solve's scalars, written by cg_reduce.comp alone; the host reads them every few
// iterations. Mirrors gpu::CgState (src/gpu/gpu_layout.h).
layout(std430, binding = 13) buffer CgState {
    float rr;         // r·r of the current residual
    float bb;         // b·b
    float alpha;      // α = r·r / p·A p of the current iteration
    float beta;       // β = r_new·z_new / r·z
    uint iterations;  // completed in this solve
    uint done;        // 0 running, 1 converged, 2 stopped (p·A p not positive: a non-finite state)
    float rz;         // r·z, z = M⁻¹ r (= r·r unpreconditioned)
    uint fromZero;    // 1: the warm start was no better than Δv = 0, the solve starts from 0
    float floor;      // ε² s·s: |r|² this small is the rounding of b's terms (cg_reduce.comp)
} cg;
// With colliders, binding 17 holds the contacts in the solve (solve_contact.glsl).
#ifdef PRECONDITIONER_JACOBI
// The inverted 3×3 diagonal blocks of A (ImplicitSystem::diagonal), two vec4 per vertex:
// [2k] = (xx, yy, zz, 0), [2k + 1] = (xy, xz, yz, 0); 0 on pinned rows.
layout(std430, binding = 14) buffer CgInverse {
    vec4 cgInverse[];
};
#endif
#endif

#ifdef INTEGRATOR_VBD
// vbd's step state (docs/integrators.md "vbd"), one vec4 per vertex: the step's displacement
// d = x − x_n (with positions, the iterate), the inertial target's ŷ = y − x_n, the previous
// step's velocity v_{n−1} (the adaptive initial guess), and the Chebyshev iterates'
// displacements d^(n−1), d^(n−2).
layout(std430, binding = 8) buffer VbdDisplacement {
    vec4 vbdDisplacement[];
};
layout(std430, binding = 9) buffer VbdInertial {
    vec4 vbdInertial[];
};
layout(std430, binding = 10) buffer VbdPrevious {
    vec4 vbdPrevious[];
};
layout(std430, binding = 11) buffer VbdBefore {
    vec4 vbdBefore[];
};
layout(std430, binding = 12) buffer VbdBeforeLast {
    vec4 vbdBeforeLast[];
};
// The translation's step (vbd_translation_*.comp): [0] = (t [m], 1 where taken), then three vec4
// per work group of the grid dispatch: (g, Σ m/h²), (H_xx, H_yy, H_zz, 0), (H_xy, H_xz, H_yz, 0).
layout(std430, binding = 14) buffer VbdTranslation {
    vec4 vbdTranslation[];
};
#ifdef HAS_COLLIDERS
// With colliders, vbd's contacts (src/cpu/cpu_vbd_phases.h VbdContacts), two vec4 per vertex:
// [2k] = (unit normal n, w = c_f λ [N]), [2k + 1] = (h v_c [m], 1 where the last Newton step's
// projection pushed along n, else 0); w = 0: no contact.
layout(std430, binding = 13) buffer VbdContacts {
    vec4 vbdContacts[];
};
#endif
#endif

int gridU() { return params.grid.x; }
int gridV() { return params.grid.y; }

bool insideGrid(ivec2 ij) {
    return ij.x >= 0 && ij.y >= 0 && ij.x < gridU() && ij.y < gridV();
}

uint vertexIndex(ivec2 ij) { return uint(ij.y) * uint(gridU()) + uint(ij.x); }
