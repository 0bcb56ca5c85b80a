// The GPU backend (DESIGN.md §3): float state in std430 SSBOs, two compute passes per step,
// no CPU round trip except a 16-byte status read every few steps.
#pragma once

#include <array>
#include <string>

#include "core/solver.h"
#include "gpu/gpu_backend.h"
#include "gpu/gpu_layout.h"
#include "gpu/gpu_variant.h"

namespace cloth {

class GlContext;

class GpuSolver final : public Solver {
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

    // GL buffer names (vec4 per vertex, k = j·nu + i): the renderer binds them as vertex
    // buffers. Valid in the context the solver was made in.
    unsigned positionBuffer() const { return buffers_[gpu::kPositions]; }
    unsigned normalBuffer() const { return buffers_[gpu::kNormals]; }

    // Seconds per step of the last step(n) call: GL timer queries where they count, else
    // glFinish and a steady clock (llvmpipe's timer reads 0 for compute).
    double lastSecondsPerStep() const { return secondsPerStep_; }
    const char* timingSource() const { return timedByQuery_ ? "GL timer query" : "wall clock"; }
    WorkGroup workGroup() const { return workGroup_; }

private:
    void upload(const Scene& scene);
    void uploadParams(const Scene& scene);
    void bindBuffers() const;
    void dispatchStep(long stepNumber) const;
    gpu::Status readStatus() const;
    StepResult reportUnstable(const gpu::Status& status, long stepsBefore);

    const GlContext& context_;
    Features features_;
    WorkGroup workGroup_;
    int nu_, nv_;
    int groupsX_, groupsY_;
    int checkEvery_;
    double maxSpeed_;
    std::string name_;
    std::array<unsigned, gpu::kBindingCount> buffers_{};
    unsigned forcesProgram_ = 0, integrateProgram_ = 0;
    unsigned timer_ = 0;
    double secondsPerStep_ = 0;
    bool timedByQuery_ = false;
};

}  // namespace cloth
