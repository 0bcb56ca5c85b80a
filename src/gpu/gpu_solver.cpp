#include "gpu/gpu_solver.h"

#include <GL/glew.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <utility>
#include <vector>

#include "gpu/egl_context.h"
#include "gpu/gpu_buffers.h"
#include "gpu/shader_loader.h"
#include "model/bending.h"
#include "model/errors.h"
#include "model/pin_follow.h"
#include "model/vbd_colouring.h"
#include "model/vbd_local.h"

namespace cloth {
namespace {

using gpu::bufferData;
using gpu::kVec4;
using gpu::vec4;

using Clock = std::chrono::steady_clock;

// Room for this many pins before setPinned has to grow the table.
constexpr std::size_t kMinPinCapacity = 16;

// The scene's kernels (kernelsOf its integrator, and many_steps.comp when `manyStepsGroup` > 0)
// with the variant's defines; none leaks if a later one fails to build.
std::array<unsigned, kKernelCount> buildPrograms(const Scene& scene, WorkGroup wg,
                                                 ForcesKernel forces, int manyStepsGroup,
                                                 const std::vector<bool>& dragged,
                                                 int storageBlockLimit, int multigridChunks) {
    const ShaderDirectory dir = findShaderDirectory();
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::is_directory(fs::path(dir.path) / "compute", ec))
        throw std::runtime_error("no compute shaders in " + dir.path +
                                 "/compute (shader directory " + dir.how +
                                 "); set CLOTH_SHADER_DIR to the project's shaders/");
    std::array<unsigned, kKernelCount> programs{};
    std::vector<Kernel> kernels = kernelsOf(
        scene.integrator.method, scene.integrator.preconditioner, !scene.colliders.empty());
    Defines extra;
    if (forces == ForcesKernel::Tiled) extra.push_back({"FORCES_TILED", ""});
    if (manyStepsGroup > 0) {
        kernels.push_back(Kernel::ManySteps);
        extra.push_back({"MANY_STEPS_GROUP", std::to_string(manyStepsGroup)});
    }
    if (scene.selfCollision)
        for (Kernel k : selfCollisionKernels()) kernels.push_back(k);
    if (Features::of(scene).stepControl) kernels.push_back(Kernel::StepCheck);
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Multigrid)
        for (const auto& define : multigridChunkDefines(multigridChunks)) extra.push_back(define);
    try {
        for (Kernel k : kernels) {
            const ShaderSource source =
                assembleKernel(dir.path, kernelFile(k), scene, wg, extra, dragged);
            checkStorageBlocks(source, storageBlockLimit);
            programs[int(k)] = compileComputeProgram(source);
        }
    } catch (...) {
        for (unsigned p : programs) glDeleteProgram(p);  // 0 is silently ignored
        throw;
    }
    return programs;
}

}  // namespace

GpuSolver::GpuSolver(const Scene& scene, const GpuOptions& options)
    : context_(GlContext::instance()),
      features_(Features::of(scene)),
      method_(scene.integrator.method),
      preconditioner_(scene.integrator.preconditioner),
      maxIterations_(scene.integrator.maxIterations),
      vbdIterations_(scene.integrator.iterations),
      chebyshevRho_(scene.integrator.chebyshevRho),
      translationSweeps_(scene.integrator.translationSweeps),
      translationLevels_(vbdTranslationLevels(scene.integrator.translationLevels,
                                              scene.integrator.translationBlockWidth,
                                              scene.cloth.nu, scene.cloth.nv)),
      translationLevelPasses_(scene.integrator.translationLevelPasses),
      forces_(options.forces),
      nu_(scene.cloth.nu),
      nv_(scene.cloth.nv),
      checkEvery_(options.checkEvery),
      maxSpeed_(scene.maxSpeed) {
    scene_ = scene;
    dragged_.assign(scene.colliders.size(), false);
    drags_.resize(scene.colliders.size());
    context_.makeCurrent();
    const GpuInfo& info = context_.info();
    if (checkEvery_ < 1)
        throw InputError("", "checkEvery",
                         "must be at least 1, not " + std::to_string(checkEvery_));
    workGroup_ =
        chooseWorkGroup({options.workGroupX, options.workGroupY}, &info, options.workGroupKey);
    checkSceneFits(scene, workGroup_, info);
    const bool multigrid = method_ == Method::ImplicitEuler &&
                           scene.integrator.preconditioner == Preconditioner::Multigrid;
    if (info.maxUniformBlockSize < static_cast<long long>(sizeof(gpu::Params)))
        throw GpuUnavailable(info.renderer + " allows " + std::to_string(info.maxUniformBlockSize) +
                             "-byte uniform blocks; the parameters need " +
                             std::to_string(sizeof(gpu::Params)));
    gpu::ColliderTable(scene).checkFits(info.maxStorageBlockSize, scene.source);
    if (forces_ == ForcesKernel::Tiled) checkTileFits(workGroup_, info);
    const long long vertices = static_cast<long long>(nu_) * nv_;
    // Self-collision runs between steps: one step a dispatch.
    if (!features_.selfCollision &&
        usesManySteps(options.dispatch, method_, vertices, info.software))
        manyStepsGroup_ = manyStepsGroupSize(vertices, info);
    multigridChunks_ = multigridChunks(info.software);
    if (features_.selfCollision) checkSelfCollisionFits(scene);
    if (features_.stepControl) checkBindingFits(gpu::kStepStart, "step control");
    groupsX_ = (nu_ + workGroup_.x - 1) / workGroup_.x;  // DESIGN.md §3: ceil, never drop the rest
    groupsY_ = (nv_ + workGroup_.y - 1) / workGroup_.y;
    // vbd's sweep: one invocation per vertex of a colour, ceil(nu/5) a row.
    vbdGroupsX_ = ((nu_ + kVbdColours - 1) / kVbdColours + workGroup_.x - 1) / workGroup_.x;
    setStepDt(scene.integrator.dt);
    compilePrograms();
    for (gpu::Binding b : {gpu::kPositions, gpu::kVelocities, gpu::kForces, gpu::kNormals,
                           gpu::kColliders, gpu::kPins, gpu::kStatus})
        glGenBuffers(1, &buffers_[b]);
    glGenBuffers(1, &paramsBuffer_);
    generateIntegratorBuffers();
    if (multigrid)
        multigrid_ = std::make_unique<GpuMultigrid>(nu_, nv_, workGroup_, multigridChunks_);
    upload(scene);
    if (features_.selfCollision) allocateSelfCollision(scene);
    if (features_.stepControl) allocateStepCheck();
    setGrabUniforms(std::nullopt);
    // llvmpipe's GL_TIME_ELAPSED reads ~0 for compute work: time software renderers by clock.
    if (info.timerQueries && !info.software) glGenQueries(1, &timer_);
    name_ = "gpu float (" + info.renderer.substr(0, info.renderer.find(" (")) + ", work groups " +
            std::to_string(workGroup_.x) + "x" + std::to_string(workGroup_.y) + ", " +
            forcesKernelName(forces_) + " forces" +
            (manySteps() ? ", many steps per dispatch in " + std::to_string(manyStepsGroup_) +
                               " invocations"
                         : "") +
            (!multigrid_ ? ""
             : multigridChunks_ == 1
                 ? ", multigrid lines as one chain"
                 : ", multigrid lines in up to " + std::to_string(multigridChunks_) + " chunks") +
            ")";
    computeNormals();  // valid before the first step, for a renderer drawing frame 0
}

void GpuSolver::compilePrograms() {
    const std::array<unsigned, kKernelCount> programs =
        buildPrograms(scene_, workGroup_, forces_, manyStepsGroup_, dragged_,
                      context_.info().maxComputeStorageBlocks, multigridChunks_);
    for (unsigned p : programs_) glDeleteProgram(p);
    programs_ = programs;
    defines_ = gpuDefines(scene_, workGroup_, dragged_);
}

GpuSolver::~GpuSolver() {
    try {
        context_.makeCurrent();
    } catch (...) {
        return;  // the context is gone; so are its objects
    }
    glDeleteBuffers(GLsizei(buffers_.size()), buffers_.data());  // 0 is silently ignored
    glDeleteBuffers(1, &paramsBuffer_);
    glDeleteBuffers(1, &stepMaxima_);
    for (unsigned p : programs_) glDeleteProgram(p);
    if (timer_ != 0) glDeleteQueries(1, &timer_);
}

// Rest positions with w = the vertex's inverse mass (0 pinned); pinned vertices keep their slot
// in the pin table in velocity.w. Conversions to float match the CPU float backend's.
void GpuSolver::upload(const Scene& scene) {
    const Grid g = scene.grid();
    const std::size_t n = std::size_t(g.count());
    std::vector<glm::vec4> x(n), v(n, glm::vec4(0));
    inverseMass_ = inverseMasses(scene);
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i) {
            const std::size_t k = std::size_t(g.index(i, j));
            x[k] = vec4(g.restPosition(i, j), inverseMass_[k]);
        }
    for (const Pin& p : scene.pins) {
        const std::int64_t k = g.index(p.i, p.j);
        if (pinSlots_.count(k) != 0) continue;  // listed twice
        x[std::size_t(k)].w = 0;
        v[std::size_t(k)].w = float(pins_.size());  // exact below 2^24 pins
        pinSlots_[k] = {int(pins_.size()), true};
        pins_.push_back(glm::vec4(glm::vec3(x[std::size_t(k)]), 0));
    }
    // A follow pin holds its rest position and its collider's FollowRecord offset + 1, and
    // starts where the collider's motion puts it at t = 0, with its velocity (as on the CPU).
    const gpu::ColliderTable colliders(scene);
    for (const FollowPin& f : followPins(scene)) {
        const std::size_t k = std::size_t(f.vertex);
        const PinState s = followPinAt(f, 0.0);
        x[k] = vec4(s.position, 0);
        v[k] = vec4(s.velocity, v[k].w);
        pins_[std::size_t(v[k].w)] =
            vec4(f.rest, float(colliders.followRecord(std::size_t(f.collider)) + 1));
        following_[f.vertex] = f.collider;
    }
    bufferData(buffers_[gpu::kPositions], x);
    bufferData(buffers_[gpu::kVelocities], v);
    bufferData(buffers_[gpu::kForces], nullptr, n * kVec4);
    bufferData(buffers_[gpu::kNormals], nullptr, n * kVec4);
    std::vector<glm::vec4> table = pins_;  // with room for setPinned
    pinCapacity_ = std::max(pins_.size(), kMinPinCapacity);
    table.resize(pinCapacity_, glm::vec4(0));
    bufferData(buffers_[gpu::kPins], table);
    const gpu::Status status = gpu::kStable;
    bufferData(buffers_[gpu::kStatus], &status, sizeof status);
    glBindBuffer(GL_UNIFORM_BUFFER, paramsBuffer_);
    glBufferData(GL_UNIFORM_BUFFER, sizeof(gpu::Params), nullptr, GL_DYNAMIC_DRAW);
    allocateIntegratorBuffers();
    uploadParams(scene);
    uploadColliders(scene);
}

void GpuSolver::uploadParams(const Scene& scene) {
    const Grid g = scene.grid();
    gpu::Params p{};
    static_assert(std::size(gpu::Params{}.restLength) == kSpringOffsets.size());
    static_assert(std::size(gpu::Params{}.stiffness) == kSpringOffsets.size());
    p.grid = glm::ivec2(nu_, nv_);
    p.dt = float(scene.integrator.dt);
    p.dampingRate = float(scene.dampingRate());
    p.gravity = glm::vec3(scene.gravity);  // as the CPU float backend converts
    p.maxSpeedSquared = float(scene.maxSpeed * scene.maxSpeed);
    p.windDirection = scene.wind ? glm::vec3(scene.wind->direction) : glm::vec3(0);
    // A material's: the pressure times an inner vertex's area; the shader halves it per border
    // (HAS_BORDER_SHARES, forces.glsl windStrengthAt), as Scene::windArea does.
    p.windStrength = scene.wind ? float(scene.wind->strength * scene.windArea(1, 1)) : 0.0f;
    p.cgTolerance = float(scene.integrator.tolerance);
    for (std::size_t o = 0; o < kSpringOffsets.size(); ++o) {
        p.stiffness[o] = float(scene.slotStiffness(int(o)));
        p.restLength[o] = float(g.restLength(kSpringOffsets[o].di, kSpringOffsets[o].dj));
    }
    const BendingWeights bending = bendingWeights(g, scene.bendingStiffness());
    p.bending[0] = float(bending.alongU);
    p.bending[1] = float(bending.alongV);
    p.bending[2] = float(bending.twist);
    p.springDamping = float(scene.springDamping());
    glBindBuffer(GL_UNIFORM_BUFFER, paramsBuffer_);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof p, &p);
}

// Pass 1 alone: fresh normals for the renderer (its forces are recomputed by the next step);
// vbd's step start, which writes them too (its x_n and y are rewritten by the next step).
void GpuSolver::computeNormals() const {
    bindBuffers();
    runPass(method_ == Method::Vbd ? Kernel::VbdStart : Kernel::Forces);
}

void GpuSolver::bindBuffers() const {
    for (unsigned b = 0; b < buffers_.size(); ++b)
        if (buffers_[b] != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers_[b]);
    glBindBufferBase(GL_UNIFORM_BUFFER, gpu::kParamsBlock, paramsBuffer_);
    if (multigrid_) multigrid_->bind();
}

// The grab's two uniforms in every kernel that includes grab.glsl: the forces pass, many steps
// per dispatch and, for implicit_euler, its right-hand side, the warm start's product and A p.
void GpuSolver::setGrabUniforms(const std::optional<Grab>& grab) const {
    for (Kernel k : {Kernel::Forces, Kernel::ManySteps, Kernel::CgRightHandSide,
                     Kernel::CgWarmStart, Kernel::CgProduct, Kernel::VbdSweep, Kernel::MgFine}) {
        const unsigned program = programs_[int(k)];
        if (program == 0) continue;
        glProgramUniform1i(program, gpu::kGrabVertexLocation, grab ? GLint(grab->vertex) : -1);
        if (!grab) continue;
        const glm::vec4 g = vec4(grab->target, grab->stiffness);  // as the CPU float converts
        glProgramUniform4f(program, gpu::kGrabLocation, g.x, g.y, g.z, g.w);
    }
}

DeviceReport GpuSolver::deviceReport() const {
    DeviceReport r;
    r.secondsPerStep = secondsPerStep_;
    r.timing = timingSource();
    r.bytes = bufferBytes();
    r.variant = std::to_string(workGroup_.x) + "x" + std::to_string(workGroup_.y) + "/" +
                forcesKernelName(forces_);
    r.dispatch = stepDispatchName(manySteps() ? StepDispatch::ManySteps : StepDispatch::PerStep);
    return r;
}

std::size_t GpuSolver::bufferBytes() const {
    context_.makeCurrent();
    std::size_t bytes = 0;
    std::vector<unsigned> all(buffers_.begin(), buffers_.end());
    all.push_back(paramsBuffer_);
    all.push_back(stepMaxima_);
    for (unsigned b : all) {
        if (b == 0) continue;
        GLint64 size = 0;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
        glGetBufferParameteri64v(GL_SHADER_STORAGE_BUFFER, GL_BUFFER_SIZE, &size);
        bytes += std::size_t(size);
    }
    if (multigrid_) bytes += multigrid_->bytes();
    return bytes;
}

gpu::Status GpuSolver::readStatus() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gpu::Status s{};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers_[gpu::kStatus]);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof s, &s);
    return s;
}

StepResult GpuSolver::step(long n) {
    StepResult result;
    if (n <= 0) return result;
    context_.makeCurrent();
    bindBuffers();
    glFinish();  // time this call's work only
    const Clock::time_point start = Clock::now();
    if (timer_ != 0) glBeginQuery(GL_TIME_ELAPSED, timer_);
    const long before = steps_;
    long done = 0;
    gpu::Status status = gpu::kStable;
    // implicit_euler reads back every step anyway (the solve's state): its status too, so no
    // solve after an unstable step is counted in solveStats_.
    const long every = method_ == Method::ImplicitEuler ? 1 : checkEvery_;
    while (done < n && status.firstBadStep == gpu::kNoBadStep) {
        const long chunk = std::min<long>(n - done, every);
        runSteps(before + done + 1, chunk);
        done += chunk;
        status = readStatus();  // the only round trip: 8 bytes every checkEvery steps
    }
    if (timer_ != 0) glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    GLuint64 ns = 0;
    if (timer_ != 0) glGetQueryObjectui64v(timer_, GL_QUERY_RESULT, &ns);
    timedByQuery_ = ns > 0;
    secondsPerStep_ = (timedByQuery_ ? double(ns) * 1e-9 : wall) / double(done);
    if (status.firstBadStep != gpu::kNoBadStep) return reportUnstable(status, before);
    steps_ += n;
    result.stepsTaken = n;
    return result;
}

SimState GpuSolver::read() const {
    context_.makeCurrent();
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // shader writes visible to the read-back
    const std::size_t n = std::size_t(nu_) * std::size_t(nv_);
    const std::vector<glm::vec4> x = gpu::downloadVec4(buffers_[gpu::kPositions], n);
    const std::vector<glm::vec4> v = gpu::downloadVec4(buffers_[gpu::kVelocities], n);
    SimState s;
    s.nu = nu_;
    s.nv = nv_;
    s.positions.resize(n);
    s.velocities.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        s.positions[k] = glm::dvec3(glm::vec3(x[k]));
        s.velocities[k] = glm::dvec3(glm::vec3(v[k]));
    }
    s.time = time();
    return s;
}

}  // namespace cloth
