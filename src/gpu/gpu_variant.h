// Which kernel a scene compiles to (DESIGN.md §3): the #defines, the work-group size and the
// checks that the grid fits the device. No GL here, so `validate` and tests can use it freely.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gpu/gpu_options.h"
#include "gpu/shader_loader.h"
#include "model/scene.h"

namespace cloth {

struct GpuInfo;

struct WorkGroup {
    int x = 16, y = 16;
};

// The work-group size to compile with, checked: InputError naming `key` (where the size came
// from) when a side is below 1 or beyond `info`'s limits; with `info` null only positivity.
WorkGroup chooseWorkGroup(WorkGroup requested, const GpuInfo* info,
                          const std::string& key = GpuOptions{}.workGroupKey);

// Throws InputError (key cloth.resolution) when the grid needs more than the device allows:
// over min(65535, device limit) work groups along a dimension, or vertex buffers larger than
// one SSBO binding may be.
void checkGridFits(const Scene& scene, WorkGroup wg, const GpuInfo& info);

// The scene's kernel variant: HAS_STRUCTURAL/HAS_SHEAR/HAS_BEND, HAS_WIND, NUM_PLANES,
// NUM_SPHERES, the colliders' defines and order (gpu::ColliderTable), the integrator, WX/WY,
// and the generated spring table. A feature the scene lacks is absent, not multiplied by zero.
// Pins and the grab are not features: the viewer changes them at run time, so their
// (one-compare) code is always there. dragged[c]: collider c is compiled as moving (the viewer
// drags it; gpu::ColliderTable).
Defines gpuDefines(const Scene& scene, WorkGroup wg, const std::vector<bool>& dragged = {});

// The compute kernels of the backend. A scene compiles the forces pass and its integrator's
// kernels only (kernelsOf); docs/integrators.md gives each scheme's passes.
enum class Kernel {
    Forces,           // pass 1 of every scheme: F and normals
    Integrate,        // explicit_euler, symplectic_euler
    VerletDrift,      // verlet: kick and drift, pins, colliders
    VerletKick,       // verlet: kick with F(x_{n+1}), pins, check
    Rk4Stage,         // rk4: one per stage, after its forces pass
    CgRightHandSide,  // implicit_euler: b (and the block-Jacobi preconditioner)
    CgWarmStart,      // implicit_euler: A Δv₀ of the last step's solution
    CgStart,          // implicit_euler: r, z, p of the CG's start
    CgProduct,        // implicit_euler: A p
    CgReduce,         // implicit_euler: the partial sums to α, β, the residual
    CgUpdate,         // implicit_euler: Δv, r
    CgDirection,      // implicit_euler: p
    ImplicitFinish,   // implicit_euler: v, x, pins, colliders, check
    VbdStart,         // vbd: the inertial target's ŷ = y − x_n, the normals
    VbdGuess,         // vbd: the initial guess, pins
    VbdSweep,         // vbd: one colour's Newton steps and contact
    VbdAccelerate,    // vbd: the Chebyshev extrapolation
    VbdFinish,        // vbd: v = d/h, pins, colliders, check
    ManySteps,        // explicit/symplectic Euler, small grids: many steps in one work group
    // implicit_euler with the multigrid preconditioner (multigrid.glsl, gpu/gpu_multigrid.h):
    CgPreconditioned,      // z of the V-cycle into the CG, r·r and r·z (p = z at the start)
    MgFine,                // the fine grid's stencil
    MgGalerkin,            // a coarse grid's stencil Pᵀ A P
    MgLines,               // a grid's line factors
    MgLineTransfers,       // their chunks' transfers
    MgCoarsestFactor,      // the coarsest grid's dense factor
    MgBegin,               // the fine r, z = 0
    MgRelaxRightHandSide,  // their right-hand sides, a vertex an invocation
    MgRelax,               // one colour of one direction's lines solved
    MgResidual,            // t = r − A z
    MgRestrict,            // r_c = Pᵀ t, z_c = 0
    MgProlong,             // z += P z_c
    MgCoarsestSolve,       // the coarsest grid solved
    // Self-collision (self_contact.glsl), after any integrator's step, when the scene declares it:
    SelfBegin,       // the step's motion and its box, y = x₀
    SelfSubstep,     // a substep's share of the motion, the sides' reference
    SelfBoxes,       // the owners' boxes, the longest edge, the buckets emptied
    SelfCount,       // the cells and the count per bucket
    SelfScanBlocks,  // the prefix sum per work group
    SelfScanSums,    // the prefix sum of the work groups' totals
    SelfScanAdd,     // the totals added
    SelfScatter,     // the vertices sorted by bucket
    SelfContacts,    // the contacts' corrections, summed in fixed point
    SelfApply,       // the mean correction, the colliders
    SelfFinish,      // the state, the velocities, the next step's start
    // implicit_euler with colliders (contacts in the solve, solve_contact.glsl):
    CgContactStart,  // Δv₀ = S Δv + the contacts' fixed part
    CgGrip,          // after the solve: each contact's grip for the next step
    // Step control (solver/step_check.h), when the scene declares it:
    StepCheck,  // each work group's largest growth of a structural spring's stretch
    // vbd's translation step (integrator.translation_sweeps):
    VbdTranslationSum,    // each work group's part of its gradient and Hessian
    VbdTranslationSolve,  // their sum, the step t
    VbdTranslationApply,  // t on every free vertex, the colliders
    // vbd's translation levels (integrator.translation_levels):
    VbdBlocks,  // one colour of one level's blocks: the sums, the step, the step applied
};
inline constexpr int kKernelCount = int(Kernel::VbdBlocks) + 1;
// The self-collision kernels, in the order above.
std::vector<Kernel> selfCollisionKernels();

const char* kernelFile(Kernel k);  // "compute/forces.comp", ...
// The kernels of an integrator, and with implicit_euler's multigrid preconditioner its own.
// `contacts`: the scene has colliders (implicit_euler solves its contacts).
std::vector<Kernel> kernelsOf(Method m, Preconditioner p = Preconditioner::Jacobi,
                              bool contacts = false);

// The bytes of the multigrid preconditioner's two buffers on an nu × nv grid
// (shaders/compute/multigrid.glsl): every level's 25 blocks of six doubles per vertex, and the
// line factors, vectors and coarsest factor, and with lines in `chunks` > 1 chunks (at most;
// multigridChunks) the chunks' transfers.
struct MultigridBytes {
    long long stencil = 0, work = 0;
};
MultigridBytes multigridBytes(int nu, int nv, int chunks);
// Throws InputError (key integrator.preconditioner) when either buffer exceeds one SSBO binding
// of `info`'s device.
void checkMultigridFits(const Scene& scene, const GpuInfo& info);
// The most chunks a line's solve is cut into (mg_relax.comp): as set (CLOTH_MULTIGRID_CHUNKS),
// else one chain a line on a software rasteriser, whose few cores the lines of a colour already
// fill (the chunks' second substitution only costs there), and kMultigridChunks on hardware.
int multigridChunks(bool software);
// Its defines: MG_CHUNKS, and MG_RELAX_GROUP, mg_relax.comp's work group (a line's chunks, or
// 64 lines of one chain each).
Defines multigridChunkDefines(int chunks);
int multigridRelaxGroup(int chunks);

// Throws InputError (naming the key) when a buffer of more than one vec4 a vertex exceeds one SSBO
// binding of `info`'s device: block-Jacobi's inverses, the step control's kept state.
void checkWideBuffersFit(const Scene& scene, WorkGroup wg, const GpuInfo& info);

// Throws InputError (naming the key) when the scene needs more of the device than it offers: its
// grid (checkGridFits), its wider buffers (checkWideBuffersFit) and, with implicit_euler's
// multigrid preconditioner, that one's buffers (checkMultigridFits). GpuSolver checks it first;
// --backend auto asks it (gpuSceneRefusal).
void checkSceneFits(const Scene& scene, WorkGroup wg, const GpuInfo& info);

// Whether a scene runs many steps per dispatch (many_steps.comp): as asked, or with Auto for
// explicit and symplectic Euler up to manyStepsMaxVertices(software). Throws InputError (key
// `dispatch`) when ManySteps is asked for another integrator.
bool usesManySteps(StepDispatch dispatch, Method method, long long vertices, bool software);

// Throws InputError (key `forces`) when forces.comp's tile of WX × WY vertices and its 2-vertex
// halo, one vec4 each, exceeds the device's shared memory per work group.
void checkTileFits(WorkGroup wg, const GpuInfo& info);
std::size_t tileBytes(WorkGroup wg);

// Invocations of many_steps.comp's one work group for a grid of `vertices`: 32 on a software
// rasteriser, the device's most per work group on hardware, fewer for a grid that has fewer
// vertices (in whole multiples of 32).
int manyStepsGroupSize(long long vertices, const GpuInfo& info);

// The assembled source of a kernel file (kernelFile) for `scene`, with `extra` defines after the
// scene's (FORCES_TILED, MANY_STEPS_GROUP).
ShaderSource assembleKernel(const std::string& dir, const std::string& file, const Scene& scene,
                            WorkGroup wg, const Defines& extra = {},
                            const std::vector<bool>& dragged = {});

}  // namespace cloth
