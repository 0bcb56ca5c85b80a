// The GPU backend (DESIGN.md §3): float state in std430 SSBOs, a forces pass and an update pass
// per force evaluation of the scene's integrator (docs/integrators.md), no CPU round trip except
// a 16-byte status read every few steps, and for implicit_euler the solve's state every few
// conjugate-gradient iterations.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/gpu_backend.h"
#include "gpu/gpu_collider_table.h"
#include "gpu/gpu_layout.h"
#include "gpu/gpu_multigrid.h"
#include "gpu/gpu_variant.h"
#include "solver/solver.h"
#include "solver/step_check.h"

namespace cloth {

class GlContext;

// With step control, it is its own StepCheck (gpu_step_check.cpp): the step's start is kept in
// a buffer and measured by a reduction pass, never read back.
class GpuSolver final : public Solver, private StepCheck {
public:
    // Throws as makeGpuSolver does.
    GpuSolver(const Scene& scene, const GpuOptions& options);
    ~GpuSolver() override;
    GpuSolver(const GpuSolver&) = delete;
    GpuSolver& operator=(const GpuSolver&) = delete;

    StepResult step(long n) override;
    SimState read() const override;
    Features features() const override { return features_; }
    std::string name() const override { return name_; }

    // Interactive control: small buffer updates and uniforms, no recompilation.
    void write(const SimState& state) override;
    void setPinned(int i, int j, bool pinned) override;
    void setGrab(const std::optional<Grab>& grab) override;
    void setParameters(const Scene& scene) override;
    // The drag is added to the collider's posed records (docs/colliders.md §9). The first drag
    // of a collider compiled as still (no motion) compiles the kernels again with it moving,
    // keeping the state; later drags and every other collider's are data.
    void setColliderDrag(int index, const glm::dvec3& offset, const glm::dvec3& velocity) override;

    std::optional<DrawBuffers> drawBuffers() const override {
        return DrawBuffers{buffers_[gpu::kPositions], buffers_[gpu::kNormals]};
    }
    DeviceReport deviceReport() const override;
    PassTimes timePasses(int repeats) override {
        return {timePass(Kernel::Forces, repeats), timePass(Kernel::Integrate, repeats)};
    }

    // Seconds per step of the last step(n) call: GL timer queries where they count, else
    // glFinish and a steady clock (llvmpipe's timer reads 0 for compute).
    double lastSecondsPerStep() const { return secondsPerStep_; }
    const char* timingSource() const { return timedByQuery_ ? "GL timer query" : "wall clock"; }
    WorkGroup workGroup() const { return workGroup_; }
    ForcesKernel forcesKernel() const { return forces_; }
    bool manySteps() const { return manyStepsGroup_ > 0; }  // many_steps.comp steps this scene
    int checkEvery() const { return checkEvery_; }
    // Seconds per dispatch of one pass over the grid alone, best of `repeats` (glFinish and a
    // steady clock): what bench speed --pass-times reports to say what limits a step. The state
    // changes as a step's would (Integrate) or not at all (Forces). NaN for a kernel the scene's
    // integrator does not compile.
    double timePass(Kernel k, int repeats);
    // Bytes of GPU memory in the solver's buffers: the state, the parameters, the tables and
    // the integrator's own (RK4's stages, the CG's vectors), which only a scene with that
    // integrator allocates.
    std::size_t bufferBytes() const;
    SelfCollisionStats selfCollisionStats() const override { return selfStats_; }
    std::vector<std::int64_t> selfContactVertices() const override;
    StepCheck* stepCheck() override { return features_.stepControl ? this : nullptr; }

private:
    struct PinSlot {
        int slot;     // row of the Pins table (velocity.w); kept when released, for re-pinning
        bool pinned;  // pinned now: position.w = 0
    };

    // The kernels of the variant scene_ and dragged_ make; the old ones stay if a build fails.
    void compilePrograms();
    void upload(const Scene& scene);
    void uploadParams(const Scene& scene);
    // The Colliders block (gpu_solver_colliders.cpp): the records and samples of `scene`; the
    // moving colliders' poses are uploaded by the batch as the steps reach them.
    void uploadColliders(const Scene& scene);
    long posedSteps(long first);
    void runSteps(long first, long count);
    // 1/m_k of every vertex as float (Scene::vertexMass), k = j·nu + i.
    static std::vector<float> inverseMasses(const Scene& scene);
    void updateInverseMass(const Scene& scene);
    void storePin(int slot);
    void computeNormals() const;
    void generateIntegratorBuffers();  // gpu_solver_buffers.cpp
    void allocateIntegratorBuffers();
    void bindBuffers() const;
    void setGrabUniforms(const std::optional<Grab>& grab) const;
    gpu::Status readStatus() const;

    // One step of the scene's integrator (gpu_solver_steps.cpp).
    void dispatchStep(long stepNumber);
    // One dispatch over the grid, or over groupsX columns of work groups (vbd's sweep: a fifth).
    void runPass(Kernel k) const { runPass(k, groupsX_); }
    void runPass(Kernel k, int groupsX) const;
    void runStepPass(Kernel k, long stepNumber) const { runStepPass(k, stepNumber, groupsX_); }
    void runStepPass(Kernel k, long stepNumber, int groupsX) const;
    void runManySteps(long firstStep, long count) const;
    void stepVerlet(long stepNumber);
    void stepRk4(long stepNumber) const;
    void stepImplicit(long stepNumber);
    void stepVbd(long stepNumber) const;
    void runVbdLevels(long stepNumber) const;
    gpu::CgState solve() const;
    void iterate() const;
    // With the multigrid preconditioner: z = V r, then z into the CG with its sums (p = z at
    // the solve's start).
    void precondition(bool start) const;
    void runReduction(gpu::CgReduction which) const;
    gpu::CgState readCgState() const;
    void recordSolve(long stepNumber, const gpu::CgState& cg);
    StepResult reportUnstable(const gpu::Status& status, long stepsBefore);
    // Self-collision (gpu_self_collision.cpp, docs/physics.md "Self-collision").
    void checkSelfCollisionFits(const Scene& scene) const;
    // Throws GpuUnavailable where the device has no storage buffer binding `binding`, which
    // `feature` needs.
    void checkBindingFits(unsigned binding, const char* feature) const;
    // After the state was replaced (write, restore): the time, a start without history (vbd's
    // v_{n−1}, implicit_euler's last solution, the forces verlet kept), no instability, normals.
    void startAfresh(double time);
    // Step control (gpu_step_check.cpp, solver/step_check.h).
    void allocateStepCheck();
    void copyKeptState(bool toKept) const;
    void keep() override;
    double stretchGrowth() override;
    void restore() override;
    double keptTime_ = 0;  // the time of the kept state
    void allocateSelfCollision(const Scene& scene);
    void setSelfUniforms(const Scene& scene) const;
    void storeSelfStart() const;  // the positions as the next step's start
    void resolveSelfContacts(long stepNumber);
    void runSelfPass(Kernel k, std::size_t invocations) const;
    void stopCollapsed(long stepNumber, unsigned vertex);
    // The reason for an instability at `status` that self-collision recorded, if it did.
    std::optional<std::string> selfCollapseReport(const gpu::Status& status) const;
    SelfCollisionStats selfStats_;
    // Where a vertex was in more contacts than its fixed-point sums hold (the cloth collapsed
    // onto itself): the step stopped there, as CpuSelfCollision::resolve stops it.
    struct SelfCollapse {
        long step;
        unsigned vertex;
        int touches;
    };
    std::optional<SelfCollapse> selfCollapse_;
    std::size_t selfBuckets_ = 0;

    const GlContext& context_;
    Features features_;
    Method method_;
    Preconditioner preconditioner_;  // implicit_euler's (a kernel variant: fixed per solver)
    int maxIterations_;              // implicit_euler's cap on CG iterations per step
    std::unique_ptr<GpuMultigrid> multigrid_;  // the "multigrid" preconditioner's hierarchy
    bool multigridTraced_ = false;             // CLOTH_MULTIGRID_TRACE: once a solver
    // vbd: sweeps per step, Chebyshev's ρ, and the first step whose v_{n−1} is in kVbdPrevious.
    int vbdIterations_;
    double chebyshevRho_;
    int translationSweeps_;       // vbd: the sweeps followed by the translation's step
    int translationLevels_;       // vbd: the translation's levels that run (vbdTranslationLevels)
    int translationLevelPasses_;  // vbd: their passes a step (vbdLevelPassSweep)
    long vbdHistoryFrom_ = 2;
    // verlet: the forces buffer holds F(x_n) of the coming step (F(x_{n+1}) of the last one).
    // Anything that changes the state or the forces from outside discards it.
    bool forcesKept_ = false;
    Defines defines_;            // the compiled variant: setParameters must not need another
    Scene scene_;                // the scene of the last setParameters (a recompilation's)
    std::vector<bool> dragged_;  // by collider: compiled as moving for a drag (ColliderTable)
    std::vector<std::optional<ColliderDrag>> drags_;  // by collider: the viewer's drags
    std::optional<Grab> grab_;                        // set again in recompiled kernels
    std::map<std::int64_t, int> following_;           // vertex k → the collider its pin follows
    WorkGroup workGroup_;
    ForcesKernel forces_;
    int manyStepsGroup_ = 0;   // many_steps.comp's invocations; 0: two dispatches per step
    int multigridChunks_ = 1;  // the most chunks of a multigrid line solve (multigridChunks)
    int nu_, nv_;
    int groupsX_, groupsY_;
    int vbdGroupsX_ = 0;  // vbd_sweep.comp's: a fifth of the columns
    int checkEvery_;
    double maxSpeed_;
    std::vector<float> inverseMass_;            // 1/m_k [1/kg], in position.w of a free vertex
    std::map<std::int64_t, PinSlot> pinSlots_;  // by vertex k: the pins and former pins
    std::vector<glm::vec4> pins_;               // host copy of the Pins table, by slot
    std::size_t pinCapacity_ = 0;               // rows allocated in the Pins buffer
    std::optional<gpu::ColliderTable> colliders_;
    std::vector<const void*> sampleSources_;       // the meshes whose samples are on the GPU
    std::size_t colliderVec4s_ = ~std::size_t(0);  // vec4s allocated in Colliders; ~0: none
    long posedFrom_ = 0, posedTo_ = 0;             // steps [from, to) whose poses are uploaded
    std::string name_;
    std::array<unsigned, gpu::kBindingCount> buffers_{};  // 0: not used by this integrator
    std::array<unsigned, kKernelCount> programs_{};       // 0: not compiled for this scene
    unsigned paramsBuffer_ = 0;  // the uniform buffer of gpu::Params, at gpu::kParamsBlock
    unsigned stepMaxima_ = 0;    // the step check's maxima, copied out for the host to read
    unsigned timer_ = 0;
    double secondsPerStep_ = 0;
    bool timedByQuery_ = false;
};

}  // namespace cloth
