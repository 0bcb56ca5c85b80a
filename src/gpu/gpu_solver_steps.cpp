// GpuSolver's steps, one function per integrator of docs/integrators.md: which passes run, in
// what order. The physics is in the kernels (shaders/compute/); between two passes a
// GL_SHADER_STORAGE_BARRIER_BIT makes the first one's writes visible to the second.
#include <GL/glew.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/gpu_solver.h"
#include "model/vbd_colouring.h"
#include "model/vbd_local.h"

namespace cloth {
namespace {

// implicit_euler: conjugate-gradient iterations between two reads of the solve's state. The
// kernels skip their work once the solve has converged, so the cost of reading less often is
// at most this many empty iterations; reading more often costs a round trip each.
constexpr int kIterationsPerRead = 8;

}  // namespace

// One dispatch over the grid (2-D, DESIGN.md §3).
void GpuSolver::runPass(Kernel k, int groupsX) const {
    glUseProgram(programs_[int(k)]);
    glDispatchCompute(GLuint(groupsX), GLuint(groupsY_), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

// A pass that writes the state (step_end.glsl): it needs the step's number.
void GpuSolver::runStepPass(Kernel k, long stepNumber, int groupsX) const {
    glProgramUniform1ui(programs_[int(k)], gpu::kStepLocation, GLuint(stepNumber));
    runPass(k, groupsX);
}

// Steps firstStep .. firstStep + count − 1 of explicit or symplectic Euler in one dispatch of one
// work group (many_steps.comp): no dispatch per pass, the barriers are inside the kernel.
void GpuSolver::runManySteps(long firstStep, long count) const {
    const unsigned program = programs_[int(Kernel::ManySteps)];
    glProgramUniform1ui(program, gpu::kStepLocation, GLuint(firstStep));
    glProgramUniform1ui(program, gpu::kStepCountLocation, GLuint(count));
    glUseProgram(program);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

double GpuSolver::timePass(Kernel k, int repeats) {
    if (programs_[int(k)] == 0) return std::nan("");  // not a kernel of this scene
    context_.makeCurrent();
    bindBuffers();
    forcesKept_ = false;
    double best = 1e300;
    for (int r = 0; r <= repeats; ++r) {  // r = 0 is the warm-up
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        if (k == Kernel::Forces) {
            runPass(k);
        } else {
            posedSteps(steps_ + 1);
            runStepPass(k, steps_ + 1);
        }
        glFinish();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (r > 0) best = std::min(best, s);
    }
    return best;
}

void GpuSolver::dispatchStep(long stepNumber) {
    switch (method_) {
        case Method::ExplicitEuler:
        case Method::SymplecticEuler:
            runPass(Kernel::Forces);
            runStepPass(Kernel::Integrate, stepNumber);
            return;
        case Method::Verlet:
            return stepVerlet(stepNumber);
        case Method::Rk4:
            return stepRk4(stepNumber);
        case Method::ImplicitEuler:
            return stepImplicit(stepNumber);
        case Method::Vbd:
            return stepVbd(stepNumber);
    }
}

// Kick–drift–kick with one force evaluation per step: F(x_{n+1}) of this step stays in the
// forces buffer as F(x_n) of the next.
void GpuSolver::stepVerlet(long stepNumber) {
    if (!forcesKept_) runPass(Kernel::Forces);
    runStepPass(Kernel::VerletDrift, stepNumber);
    runPass(Kernel::Forces);
    runStepPass(Kernel::VerletKick, stepNumber);
    forcesKept_ = true;
}

// Four stages, each a forces pass at the stage state and a stage pass (rk4_stage.comp).
void GpuSolver::stepRk4(long stepNumber) const {
    for (int stage = 0; stage < 4; ++stage) {
        runPass(Kernel::Forces);
        glProgramUniform1i(programs_[int(Kernel::Rk4Stage)], gpu::kStageLocation, stage);
        runStepPass(Kernel::Rk4Stage, stepNumber);
    }
}

// Backward Euler linearised at x_n: forces, the right-hand side, the warm start from the last
// step's Δv (or 0 where it is no better), with colliders the contacts' first guess, the CG's
// start, the solve, then the update of v and x.
void GpuSolver::stepImplicit(long stepNumber) {
    const bool contacts = programs_[int(Kernel::CgContactStart)] != 0;
    runPass(Kernel::Forces);
    if (contacts)  // the contacts' colliders are the step's
        runStepPass(Kernel::CgRightHandSide, stepNumber);
    else
        runPass(Kernel::CgRightHandSide);
    runReduction(gpu::kReduceStart);
    if (multigrid_) multigrid_->linearise(programs_);
    runPass(Kernel::CgWarmStart);
    runReduction(gpu::kReduceWarm);
    if (contacts) {  // Δv₀ with the contacts' z n, its product, |r|²
        runPass(Kernel::CgContactStart);
        runPass(Kernel::CgWarmStart);
        runReduction(gpu::kReduceContactStart);
    }
    runPass(Kernel::CgStart);
    if (multigrid_) precondition(true);
    if (multigrid_ && gpuSetup().traceMultigrid && !multigridTraced_) {
        std::fprintf(stderr, "clothsim: multigrid trace, step %ld, the solve's first V-cycle:\n%s",
                     stepNumber, multigrid_->describe().c_str());
        multigridTraced_ = true;
    }
    runReduction(gpu::kReduceStartDirection);
    recordSolve(stepNumber, solve());
    if (contacts) runStepPass(Kernel::CgGrip, stepNumber);  // reads x_n, which the finish writes
    runStepPass(Kernel::ImplicitFinish, stepNumber);
}

// vbd (docs/integrators.md "vbd"; src/cpu/cpu_vbd.cpp stepVbd, pass for pass): the start and
// the initial guess, `iterations` sweeps of one dispatch per colour (the translation's levels
// before the first and, with more passes, before sweeps spread over the rest; the first
// translation_sweeps followed by the translation's step; each with ρ > 0 by the Chebyshev
// extrapolation), then the end of the step.
void GpuSolver::stepVbd(long stepNumber) const {
    runPass(Kernel::VbdStart);
    glProgramUniform1i(programs_[int(Kernel::VbdGuess)], gpu::kVbdLocation,
                       stepNumber >= vbdHistoryFrom_ ? 1 : 0);
    runStepPass(Kernel::VbdGuess, stepNumber);
    const int passes = translationLevels_ > 0 ? translationLevelPasses_ : 0;
    const int chebyshevStart = vbdChebyshevStart(translationSweeps_, vbdIterations_, passes);
    double omega = 1;
    for (int n = 1; n <= vbdIterations_; ++n) {
        if (vbdLevelsBefore(n, vbdIterations_, passes)) runVbdLevels(stepNumber);
        for (int colour = 0; colour < kVbdColours; ++colour) {
            glProgramUniform1i(programs_[int(Kernel::VbdSweep)], gpu::kVbdLocation, colour);
            runStepPass(Kernel::VbdSweep, stepNumber, vbdGroupsX_);  // the colour's columns
        }
        if (n <= translationSweeps_) {
            runStepPass(Kernel::VbdTranslationSum, stepNumber);
            glUseProgram(programs_[int(Kernel::VbdTranslationSolve)]);
            glDispatchCompute(1, 1, 1);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            runStepPass(Kernel::VbdTranslationApply, stepNumber);
        }
        if (chebyshevRho_ > 0) {
            omega = vbdChebyshevOmega(n, chebyshevStart, chebyshevRho_, omega);
            glProgramUniform1f(programs_[int(Kernel::VbdAccelerate)], gpu::kVbdLocation,
                               float(omega));
            runStepPass(Kernel::VbdAccelerate, stepNumber);
        }
    }
    runStepPass(Kernel::VbdFinish, stepNumber);
}

// The translation's levels (vbd_blocks.comp), coarse to fine, a colour at a time. A level's
// (parts/2)² blocks of a colour take one work group each; blocks of fewer than kLevelGroupBlock
// vertices one invocation each; the first levels' large blocks are cut into chunks of at least
// kLevelChunk vertices, up to kLevelGroups work groups a colour (and what vbdTranslation holds),
// in two passes: the chunks' sums, then each chunk's work group takes its block's step from them
// (the same in each) and applies it.
void GpuSolver::runVbdLevels(long stepNumber) const {
    constexpr int kLevelChunk = 1024, kLevelGroups = 128, kLevelGroupBlock = 256;
    const unsigned program = programs_[int(Kernel::VbdBlocks)];
    glProgramUniform1ui(program, gpu::kStepLocation, GLuint(stepNumber));
    glUseProgram(program);
    const int room = 3 * groupsX_ * groupsY_;  // vec4 after vbdTranslation[0]
    const auto pass = [&](int parts, int colour, int chunks, int mode, int groups) {
        glProgramUniform4i(program, gpu::kVbdLocation, parts, colour, chunks, mode);
        glDispatchCompute(GLuint(groups), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    };
    for (int parts = 2; parts <= vbdLevelParts(translationLevels_, nu_, nv_); parts *= 2) {
        const int blocks = (parts / 2) * (parts / 2), count = (nu_ / parts) * (nv_ / parts);
        const int chunks = std::max(
            1, std::min({kLevelGroups / blocks, count / kLevelChunk, room / (3 * blocks)}));
        for (int colour = 0; colour < 4; ++colour) {
            if (count < kLevelGroupBlock) {
                pass(parts, colour, 1, 4, (blocks + 255) / 256);
                continue;
            }
            if (chunks == 1) {
                pass(parts, colour, 1, 0, blocks);
                continue;
            }
            pass(parts, colour, chunks, 1, blocks * chunks);
            pass(parts, colour, chunks, 3, blocks * chunks);
        }
    }
}

// Iterations in chunks of kIterationsPerRead until the GPU says the solve is done (converged,
// or stopped by a non-finite state) or max_iterations were dispatched. Returns the last state
// read.
gpu::CgState GpuSolver::solve() const {
    int dispatched = 0;
    gpu::CgState cg{};
    do {
        const int chunk = std::min(kIterationsPerRead, maxIterations_ - dispatched);
        for (int i = 0; i < chunk; ++i) iterate();
        dispatched += chunk;
        cg = readCgState();
    } while (cg.done == gpu::kCgRunning && dispatched < maxIterations_);
    return cg;
}

// One CG iteration (docs/integrators.md): α = r·z / p·A p; Δv += α p; r −= α A p;
// z = M⁻¹ r; β = r_new·z_new / r·z; p = z + β p. The dot products never leave the GPU; M⁻¹ is
// part of the update and direction passes, or with multigrid its own passes between them.
void GpuSolver::iterate() const {
    runPass(Kernel::CgProduct);
    runReduction(gpu::kReduceAlpha);
    runPass(Kernel::CgUpdate);
    if (multigrid_) precondition(false);
    runReduction(gpu::kReduceBeta);
    runPass(Kernel::CgDirection);
}

// The V-cycle on r (gpu_multigrid.h), then cg_preconditioned.comp: r·z (and r·r) summed after
// it, as the CPU's loop does (src/cpu/cpu_implicit.cpp).
void GpuSolver::precondition(bool start) const {
    multigrid_->apply(programs_);
    glProgramUniform1i(programs_[int(Kernel::CgPreconditioned)], gpu::kPreconditionedStartLocation,
                       start ? 1 : 0);
    runPass(Kernel::CgPreconditioned);
}

// The second level of a dot product: one work group over the partial sums.
void GpuSolver::runReduction(gpu::CgReduction which) const {
    glUseProgram(programs_[int(Kernel::CgReduce)]);
    glUniform1i(gpu::kReductionLocation, which);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

gpu::CgState GpuSolver::readCgState() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gpu::CgState cg{};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[gpu::kCgState]);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof cg, &cg);
    return cg;
}

// A solve that did not converge (max_iterations reached, or stopped: a breakdown) is a miss: the
// step went on with the last iterate, and callers report it (docs/integrators.md: never silent).
void GpuSolver::recordSolve(long stepNumber, const gpu::CgState& cg) {
    const double residual = cg.bb > 0 ? std::sqrt(double(cg.rr) / double(cg.bb)) : 0.0;
    solveStats_.record(stepNumber, int(cg.iterations), residual, cg.done == gpu::kCgConverged,
                       cg.done == gpu::kCgStopped);
}

// The shader recorded the exact first bad step and the lowest vertex bad at it (atomicMin), and
// froze the state after that step, so the range is that one step although the host looked only
// every checkEvery steps, and the vertex is the one the CPU names. Its kind and speed are read
// from that state as the shader tested them; or self-collision stopped the step (the host knows).
StepResult GpuSolver::reportUnstable(const gpu::Status& status, long stepsBefore) {
    StepResult r;
    r.unstable = true;
    forcesKept_ = false;
    r.firstBadStep = r.lastBadStep = long(status.firstBadStep);
    steps_ = long(status.firstBadStep);
    r.stepsTaken = std::max(0L, steps_ - stepsBefore);
    if (std::optional<std::string> self = selfCollapseReport(status)) {  // self-collision's
        r.reason = *self;
        return r;
    }
    const unsigned k = status.badVertex;
    if (k >= unsigned(nu_) * unsigned(nv_)) {  // every report pairs the step with a vertex
        r.reason =
            "unstable at step " + std::to_string(status.firstBadStep) + " (no vertex recorded)";
        return r;
    }
    glm::vec4 p, v;
    for (auto [binding, to] : {std::pair{gpu::kPositions, &p}, std::pair{gpu::kVelocities, &v}}) {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[binding]);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(k * gpu::kVec4), gpu::kVec4, to);
    }
    const float speed2 = glm::dot(glm::vec3(v), glm::vec3(v));
    const int i = int(k % unsigned(nu_)), j = int(k / unsigned(nu_));
    char buf[160];
    if (!std::isfinite(p.x + p.y + p.z) || !std::isfinite(speed2))
        std::snprintf(buf, sizeof buf, "non-finite position or velocity at vertex (%d, %d)", i, j);
    else
        std::snprintf(buf, sizeof buf, "speed %.3g m/s > max_speed %g m/s at vertex (%d, %d)",
                      double(std::sqrt(speed2)), maxSpeed_, i, j);
    r.reason = buf;
    return r;
}

}  // namespace cloth
