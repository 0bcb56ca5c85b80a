// C++ mirrors of the blocks in shaders/compute/layout.glsl (DESIGN.md §3): the std140 uniform
// block Params and the std430 storage blocks. The static_asserts keep each member at the offset
// the GLSL layout rules give it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace cloth::gpu {

// Binding points of the shader storage blocks, as in layout.glsl.
enum Binding : unsigned {
    kPositions = 0,   // vec4 per vertex: xyz [m], w inverse mass 1/m_k [1/kg], 0 when pinned
    kVelocities = 1,  // vec4 per vertex: xyz [m/s], w the pinned vertex's slot in kPins
    kForces = 2,      // vec4 per vertex: spring + wind force [N]
    kNormals = 3,     // vec4 per vertex: unit normal (0 where undefined)
    // 4 is free: the parameters are a uniform block (kParamsBlock), not a storage block.
    kColliders = 5,  // collider records, SDF samples, pose batch (gpu_collider_table.h)
    kPins = 6,       // vec4 per pin: pinned position [m]
    kStatus = 7,     // one Status
    // The integrator's own buffers from 8 on: only its scene compiles and allocates them.
    // rk4: the step's start and the sums k1 + 2 k2 + 2 k3 (vec4 per vertex).
    kRk4StartPositions = 8,
    kRk4StartVelocities = 9,
    kRk4SumPositions = 10,
    kRk4SumVelocities = 11,
    // implicit_euler's conjugate gradient: Δv, r, p, A p (vec4 per vertex), two float partial
    // sums per work group of the grid dispatch, one CgState, and with the block-Jacobi
    // preconditioner the inverted diagonal blocks (two vec4 per vertex).
    kCgVelocityChange = 8,
    kCgResidual = 9,
    kCgDirection = 10,
    kCgProduct = 11,
    kCgPartials = 12,
    kCgState = 13,
    kCgInverse = 14,
    // vbd: the step's displacement d = x − x_n, the inertial target's ŷ = y − x_n, the previous
    // velocity, the Chebyshev iterates' displacements n − 1 and n − 2 (vec4 per vertex).
    kVbdDisplacement = 8,
    kVbdInertial = 9,
    kVbdPrevious = 10,
    kVbdBefore = 11,
    kVbdBeforeLast = 12,
    kVbdContacts = 13,     // with colliders: (n, c_f λ), (h v_c, pushed) per vertex
    kVbdTranslation = 14,  // the translation's step t, then 3 vec4 per work group
    // Self-collision (self_contact.glsl): seven vec4 per vertex, and its integers (the hash, the
    // fixed-point sums, the header); any integrator's scene may declare it.
    kSelfVectors = 15,
    kSelfInts = 16,
    // implicit_euler with colliders: the contacts in the solve (solve_contact.glsl), three vec4
    // per vertex: (n, z), (hold, grip), (b, stuck).
    kCgContacts = 17,
    // Step control (step_check.comp), any integrator's scene that declares it: the kept
    // positions, the kept velocities (n vec4 each), then each work group's largest stretch
    // growth (in x of one vec4 per group of the grid dispatch).
    kStepStart = 18,
    kBindingCount = 19
};

// Uniform locations. The kernels that end a step (step_end.glsl): the 1-based global step
// number (many_steps.comp: its first step, and the number of steps); rk4_stage.comp also the
// stage 0..3. The kernels that include grab.glsl: the grab (Solver::setGrab), int vertex (-1:
// none) and vec4 (target [m], stiffness [N/m]). cg_reduce.comp: which sum it reduces
// (CgReduction). many_steps.comp includes both, so the step's locations differ from the grab's.
inline constexpr int kStepLocation = 2, kStageLocation = 1, kStepCountLocation = 3;
inline constexpr int kGrabVertexLocation = 0, kGrabLocation = 1;
inline constexpr int kReductionLocation = 0;
// vbd's kernels: the guess whether v_{n−1} is there (int), the sweep its colour (int), the
// Chebyshev extrapolation ω (float).
inline constexpr int kVbdLocation = 3;
// cg_preconditioned.comp: whether it starts the solve (int; p = z).
inline constexpr int kPreconditionedStartLocation = 6;
// self_contact.glsl: h [m], μ, the fixed point's units per metre, a substep's share of the step.
inline constexpr int kSelfThicknessLocation = 20, kSelfFrictionLocation = 21,
                     kSelfFixedScaleLocation = 22, kSelfShareLocation = 23;
// Self-collision's integers: the header's ints, the vertex arrays' (per vertex), the buckets'.
inline constexpr std::size_t kSelfHeaderInts = 16, kSelfIntsPerVertex = 10;
enum CgReduction : int {
    kReduceStart = 0,
    kReduceAlpha = 1,
    kReduceBeta = 2,
    kReduceWarm = 3,
    kReduceStartDirection = 4,
    kReduceContactStart = 5
};

// The uniform-block binding point of Params (its own namespace, apart from the storage blocks').
inline constexpr unsigned kParamsBlock = 0;

// The scene's parameters, read by every kernel: layout.glsl's std140 uniform block Params. std140
// puts a vec3 at a multiple of 16 and lets a float fill the vec3's last 4 bytes, and starts an
// array of vec4 at a multiple of 16; every member here is one named quantity. Uploaded whole by
// GpuSolver::uploadParams.
struct Params {
    glm::ivec2 grid;        // nu, nv [vertices]
    float dt;               // Δt [s]
    float dampingRate;      // c [1/s]: the drag on vertex k is −c·m_k·v_k (Scene::dampingRate)
    glm::vec3 gravity;      // g [m/s²]
    float maxSpeedSquared;  // max_speed² [m²/s²]: a faster vertex makes the step unstable
    glm::vec3 windDirection;  // unit; 0 without wind
    float windStrength;       // K_w [N] (a material's: K_w [N/m²] × du·dv); 0 without wind
    float cgTolerance;        // implicit_euler's relative CG tolerance on |r| / |b| [1]
    // K and L of spring-table slot o (kSpringOffsets[o]) at [o] [N/m], [m] (Scene::slotStiffness,
    // Grid::restLength). GLSL declares each vec4[3], read at [o / 4][o % 4]: std140 strides a
    // float[12] at 16 bytes per element, four times the room, while a vec4 array packs tightly
    // and is laid out exactly as a float[12]. The first starts on 16 bytes, after 12 unused.
    alignas(16) float stiffness[12];
    float restLength[12];
    // A material's bending energy (model/bending.h): w_u, w_v, t inside the sheet [N/m], and 0;
    // all 0 when the scene has none (then no kernel reads it: HAS_BENDING is not defined).
    float bending[4];
    // β [s] of the damping along the springs (Scene::springDamping): spring s adds
    // β K_s ((v_q − v_k)·d̂) d̂; 0 when the scene has none (HAS_SPRING_DAMPING not defined).
    float springDamping;
    float unused[3];  // std140 rounds the block to 16 bytes
};
static_assert(sizeof(Params) == 192);
static_assert(offsetof(Params, grid) == 0);
static_assert(offsetof(Params, dt) == 8);
static_assert(offsetof(Params, dampingRate) == 12);
static_assert(offsetof(Params, gravity) == 16);
static_assert(offsetof(Params, maxSpeedSquared) == 28);
static_assert(offsetof(Params, windDirection) == 32);
static_assert(offsetof(Params, windStrength) == 44);
static_assert(offsetof(Params, cgTolerance) == 48);
static_assert(offsetof(Params, stiffness) == 64);
static_assert(offsetof(Params, restLength) == 112);
static_assert(offsetof(Params, bending) == 160);
static_assert(offsetof(Params, springDamping) == 176);
// GL guarantees every device at least this many bytes per uniform block
// (GL_MAX_UNIFORM_BLOCK_SIZE); GpuSolver still checks the device's own value.
inline constexpr std::size_t kMinUniformBlockSize = 16384;
static_assert(sizeof(Params) <= kMinUniformBlockSize);

// Written by step_end.glsl when a vertex goes bad (DESIGN.md §2 "Instability").
struct Status {
    std::uint32_t firstBadStep;  // 1-based global step, atomicMin; kNoBadStep while stable
    std::uint32_t badVertex;     // the lowest k that went bad at that step, atomicMin
};
static_assert(sizeof(Status) == 8);
static_assert(offsetof(Status, firstBadStep) == 0);
static_assert(offsetof(Status, badVertex) == 4);
inline constexpr std::uint32_t kNoBadStep = 0xffffffffu;
inline constexpr Status kStable{kNoBadStep, 0xffffffffu};

// implicit_euler's solve scalars, written by cg_reduce.comp (layout.glsl's CgState).
struct CgState {
    float rr;                  // r·r of the current residual
    float bb;                  // b·b
    float alpha, beta;         // of the current iteration
    std::uint32_t iterations;  // completed in this solve
    std::uint32_t done;        // kCgRunning, kCgConverged or kCgStopped
    float rz;                  // r·z, z = M⁻¹ r
    std::uint32_t fromZero;    // 1: the solve started from Δv = 0, not the warm start
    float floor;  // ε² s·s, the rounding of b's terms: |r|² below it stops the solve
};
static_assert(sizeof(CgState) == 36);
static_assert(offsetof(CgState, rr) == 0);
static_assert(offsetof(CgState, bb) == 4);
static_assert(offsetof(CgState, alpha) == 8);
static_assert(offsetof(CgState, beta) == 12);
static_assert(offsetof(CgState, iterations) == 16);
static_assert(offsetof(CgState, done) == 20);
static_assert(offsetof(CgState, rz) == 24);
static_assert(offsetof(CgState, fromZero) == 28);
static_assert(offsetof(CgState, floor) == 32);
inline constexpr std::uint32_t kCgRunning = 0, kCgConverged = 1, kCgStopped = 2;

// The records of the Colliders block (shaders/compute/scene_colliders.glsl, docs/colliders.md
// §9), each a run of vec4s: a collider's record is its ContactRecord (unless it is DESIGN.md §2's
// plain plane or sphere), its shape's record, and for a moving collider its VelocityRecord.
struct ContactRecord {
    glm::vec4 params;  // x thickness h [m], y friction c_f, zw 0
};
struct PlaneRecord {
    glm::vec4 point;   // xyz [m]
    glm::vec4 normal;  // xyz unit
};
struct SphereRecord {
    glm::vec4 center;  // xyz [m], w radius [m]
};
struct BoxRecord {
    glm::vec4 center;       // xyz [m]
    glm::vec4 halfExtents;  // xyz [m]
    glm::vec4 rotation[3];  // columns: the box's axes in the world (xyz)
};
struct CapsuleRecord {
    glm::vec4 a;  // xyz end point [m], w radius [m]
    glm::vec4 b;  // xyz end point [m]
};
struct MeshRecord {
    glm::vec4 grid;         // xyz the grid's sample (0, 0, 0) in the mesh frame [m], w cell [m]
    glm::ivec4 count;       // xyz samples per axis, w the first sample's float index in the block
    glm::vec4 rotation[3];  // columns: mesh frame → world
    glm::vec4 translation;  // xyz [m]
};
struct VelocityRecord {  // docs/colliders.md §3: v_c(p) = linear + angular × (p − origin)
    glm::vec4 linear;    // xyz [m/s]
    glm::vec4 angular;   // xyz [rad/s]
    glm::vec4 origin;    // xyz [m]
};
// A followed collider's motion at the end of a step, for its follow pins (docs/colliders.md §5,
// §9): x(t) = rotation·x₀ + translation, v = linear + angular × (x − origin). The motion alone:
// a viewer's drag moves the collider, not the pins that follow it (as on the CPU).
struct FollowRecord {
    glm::vec4 rotation[3];  // columns
    glm::vec4 translation;  // xyz [m]
    VelocityRecord velocity;
};
static_assert(sizeof(ContactRecord) == 16);
static_assert(sizeof(PlaneRecord) == 32 && offsetof(PlaneRecord, normal) == 16);
static_assert(sizeof(SphereRecord) == 16);
static_assert(sizeof(BoxRecord) == 80 && offsetof(BoxRecord, halfExtents) == 16 &&
              offsetof(BoxRecord, rotation) == 32);
static_assert(sizeof(CapsuleRecord) == 32 && offsetof(CapsuleRecord, b) == 16);
static_assert(sizeof(MeshRecord) == 96 && offsetof(MeshRecord, count) == 16 &&
              offsetof(MeshRecord, rotation) == 32 && offsetof(MeshRecord, translation) == 80);
static_assert(sizeof(VelocityRecord) == 48 && offsetof(VelocityRecord, angular) == 16 &&
              offsetof(VelocityRecord, origin) == 32);

static_assert(sizeof(FollowRecord) == 112 && offsetof(FollowRecord, translation) == 48 &&
              offsetof(FollowRecord, velocity) == 64);

static_assert(sizeof(glm::vec4) == 16 && sizeof(glm::ivec4) == 16);
static_assert(sizeof(glm::vec3) == 12 && alignof(glm::vec3) == 4 && sizeof(glm::ivec2) == 8);

}  // namespace cloth::gpu
