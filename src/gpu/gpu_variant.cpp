#include "gpu/gpu_variant.h"

#include <algorithm>
#include <cstdlib>
#include <regex>

#include "gpu/egl_context.h"
#include "gpu/gpu_collider_table.h"
#include "model/errors.h"
#include "model/multigrid_levels.h"
#include "model/stiffness.h"
#include "solver/solver.h"

namespace cloth {
namespace {

// DESIGN.md §3: no dispatch dimension may exceed 65535 work groups, whatever the device says.
constexpr long long kMaxGroupsPerDimension = 65535;
constexpr long long kBytesPerVertexBuffer = 16;  // one vec4 per vertex
constexpr int kTileHalo = 2;                     // forces_tile.glsl: the bend springs' reach
// many_steps.comp's invocations on a software rasteriser: llvmpipe runs a work group on one
// thread whatever its size and each barrier switches between its 8-wide slices, so few
// invocations doing many vertices each cost least (measured: 32 to 64 best, 1024 3x slower at
// 16², docs/performance.md). A hardware GPU gets the most it allows per work group.
constexpr long long kManyStepsGroupSoftware = 32;

std::string integratorDefine(Method m) {
    switch (m) {
        case Method::ExplicitEuler:
            return "INTEGRATOR_EXPLICIT_EULER";
        case Method::SymplecticEuler:
            return "INTEGRATOR_SYMPLECTIC_EULER";
        case Method::Verlet:
            return "INTEGRATOR_VERLET";
        case Method::Rk4:
            return "INTEGRATOR_RK4";
        case Method::ImplicitEuler:
            return "INTEGRATOR_IMPLICIT_EULER";
        case Method::Vbd:
            return "INTEGRATOR_VBD";
    }
    throw InputError("", "integrator.method",
                     std::string("'") + methodName(m) + "' has no GPU kernel");
}

// The rows of kSpringOffsets whose family the scene models, as GLSL ivec4(di, dj, family,
// slot): the shader's one spring loop walks exactly these (src/model/grid.h, the seed's Q10),
// each with the stiffness of its slot.
std::pair<int, std::string> springTable(const Scene& scene) {
    int count = 0;
    std::string rows;
    for (std::size_t o = 0; o < kSpringOffsets.size(); ++o) {
        const SpringOffset& s = kSpringOffsets[o];
        if (!familyModelled(scene, s.family)) continue;
        rows += (count++ ? ", " : "") + std::string("ivec4(") + std::to_string(s.di) + ", " +
                std::to_string(s.dj) + ", " + std::to_string(int(s.family)) + ", " +
                std::to_string(o) + ")";
    }
    return {count, rows};
}

// The multigrid hierarchy compiled in (shaders/compute/multigrid.glsl): per level ivec4(nu, nv,
// the vertices of the levels above, 0), and the vertices of all levels.
void appendMultigridDefines(Defines& d, int nu, int nv) {
    std::string rows;
    long long first = 0;
    const std::vector<MultigridLevel> levels = multigridLevels(nu, nv);
    for (const MultigridLevel& l : levels) {
        rows += (rows.empty() ? "" : ", ") + std::string("ivec4(") + std::to_string(l.nu) + ", " +
                std::to_string(l.nv) + ", " + std::to_string(first) + ", 0)";
        first += l.count();
    }
    d.push_back({"PRECONDITIONER_MULTIGRID", ""});
    d.push_back({"MG_LEVEL_COUNT", std::to_string(levels.size())});
    d.push_back({"MG_LEVELS", rows});
    d.push_back({"MG_TOTAL", std::to_string(first)});
}

}  // namespace

MultigridBytes multigridBytes(int nu, int nv, int chunks) {
    long long total = 0, lines = 0;
    const std::vector<MultigridLevel> levels = multigridLevels(nu, nv);
    for (const MultigridLevel& l : levels) total += l.count();
    // Every relaxed level's rows and columns: 128 doubles of transfers a chunk (transferAt),
    // where a line is cut into chunks at all.
    if (chunks > 1)
        for (std::size_t l = 0; l + 1 < levels.size(); ++l) lines += levels[l].nu + levels[l].nv;
    const long long coarsestDofs = 3 * levels.back().count();
    constexpr long long kDouble = 8;
    return {total * 25 * 9 * kDouble,
            (63 * total + coarsestDofs * coarsestDofs + lines * chunks * 128) * kDouble};
}

int multigridChunks(bool software) {
    if (gpuSetup().multigridChunks > 0) return gpuSetup().multigridChunks;
    return software ? 1 : kMultigridChunks;
}

int multigridRelaxGroup(int chunks) {
    return chunks == 1 ? 64 : chunks;
}

Defines multigridChunkDefines(int chunks) {
    return {{"MG_CHUNKS", std::to_string(chunks)},
            {"MG_RELAX_GROUP", std::to_string(multigridRelaxGroup(chunks))}};
}

void checkMultigridFits(const Scene& scene, const GpuInfo& info) {
    const MultigridBytes bytes =
        multigridBytes(scene.cloth.nu, scene.cloth.nv, multigridChunks(info.software));
    const long long largest = std::max(bytes.stencil, bytes.work);
    if (largest <= info.maxStorageBlockSize) return;
    throw InputError(scene.source, "integrator.preconditioner",
                     "\"multigrid\" on the " + std::to_string(scene.cloth.nu) + "x" +
                         std::to_string(scene.cloth.nv) + " grid needs a " +
                         std::to_string(largest) +
                         "-byte buffer of its stencils (2.4 kB a vertex); " + info.renderer +
                         " allows at most " + std::to_string(info.maxStorageBlockSize) +
                         " bytes per SSBO: use \"jacobi\", a coarser grid or the CPU backend");
}

void checkWideBuffersFit(const Scene& scene, WorkGroup wg, const GpuInfo& info) {
    const int nu = scene.cloth.nu, nv = scene.cloth.nv;
    const long long n = static_cast<long long>(nu) * nv;
    const long long groups = ((nu + wg.x - 1LL) / wg.x) * ((nv + wg.y - 1LL) / wg.y);
    auto refuse = [&](long long bytes, const char* key, const std::string& what) {
        if (bytes <= info.maxStorageBlockSize) return;
        throw InputError(scene.source, key,
                         what + " on the " + std::to_string(nu) + "x" + std::to_string(nv) +
                             " grid need a " + std::to_string(bytes) + "-byte buffer; " +
                             info.renderer + " allows at most " +
                             std::to_string(info.maxStorageBlockSize) +
                             " bytes per SSBO: a coarser grid or the CPU backend");
    };
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Jacobi)
        refuse(2 * n * kBytesPerVertexBuffer, "integrator.preconditioner",
               "\"jacobi\"'s inverse blocks (two vec4 a vertex)");
    if (Features::of(scene).stepControl)
        refuse((2 * n + groups) * kBytesPerVertexBuffer, "integrator.max_step_strain",
               "the step control's kept positions and velocities (two vec4 a vertex)");
}

void checkSceneFits(const Scene& scene, WorkGroup wg, const GpuInfo& info) {
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Aggregation)
        throw InputError(scene.source, "integrator.preconditioner",
                         "\"aggregation\" runs on the CPU backend only (its per-step setup has no "
                         "GPU kernels): use \"multigrid\" on the GPU or --backend cpu");
    checkGridFits(scene, wg, info);
    checkWideBuffersFit(scene, wg, info);
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Multigrid)
        checkMultigridFits(scene, info);
}

WorkGroup chooseWorkGroup(WorkGroup wg, const GpuInfo* info, const std::string& key) {
    const std::string size = std::to_string(wg.x) + "x" + std::to_string(wg.y);
    if (wg.x < 1 || wg.y < 1) throw InputError("", key, size + ": sizes must be at least 1");
    if (info == nullptr) return wg;
    if (wg.x > info->maxWorkGroupSize[0] || wg.y > info->maxWorkGroupSize[1])
        throw InputError("", key,
                         size + " exceeds the device's work-group size limit " +
                             std::to_string(info->maxWorkGroupSize[0]) + "x" +
                             std::to_string(info->maxWorkGroupSize[1]));
    if (static_cast<long long>(wg.x) * wg.y > info->maxInvocations)
        throw InputError("", key,
                         size + " is " + std::to_string(static_cast<long long>(wg.x) * wg.y) +
                             " invocations; the device allows at most " +
                             std::to_string(info->maxInvocations) + " per work group");
    return wg;
}

void checkGridFits(const Scene& scene, WorkGroup wg, const GpuInfo& info) {
    const int nu = scene.cloth.nu, nv = scene.cloth.nv;
    const std::string grid = std::to_string(nu) + "x" + std::to_string(nv);
    const long long groups[2] = {(nu + wg.x - 1LL) / wg.x, (nv + wg.y - 1LL) / wg.y};
    for (int d = 0; d < 2; ++d) {
        const long long limit =
            std::min<long long>(kMaxGroupsPerDimension, info.maxWorkGroupCount[d]);
        if (groups[d] <= limit) continue;
        throw InputError(scene.source, "cloth.resolution",
                         "grid " + grid + " needs " + std::to_string(groups[d]) +
                             " work groups along " + (d == 0 ? "u" : "v") + " with " +
                             std::to_string(wg.x) + "x" + std::to_string(wg.y) +
                             " work groups; the GPU backend dispatches at most " +
                             std::to_string(limit) +
                             " per dimension (a larger CLOTH_WORKGROUP "
                             "along that side may help)");
    }
    const long long bytes = static_cast<long long>(nu) * nv * kBytesPerVertexBuffer;
    if (bytes > info.maxStorageBlockSize)
        throw InputError(scene.source, "cloth.resolution",
                         "grid " + grid + " needs " + std::to_string(bytes) +
                             "-byte vertex buffers; " + info.renderer + " allows at most " +
                             std::to_string(info.maxStorageBlockSize) + " bytes per SSBO (" +
                             std::to_string(info.maxStorageBlockSize / kBytesPerVertexBuffer) +
                             " vertices)");
}

Defines gpuDefines(const Scene& scene, WorkGroup wg, const std::vector<bool>& dragged) {
    const Features f = Features::of(scene);
    Defines d;
    if (f.structural) d.push_back({"HAS_STRUCTURAL", ""});
    if (f.shear) d.push_back({"HAS_SHEAR", ""});
    if (f.bend) d.push_back({"HAS_BEND", ""});
    if (f.wind) d.push_back({"HAS_WIND", ""});
    if (f.bending) d.push_back({"HAS_BENDING", ""});
    if (f.borderShares) d.push_back({"HAS_BORDER_SHARES", ""});
    if (f.springDamping) d.push_back({"HAS_SPRING_DAMPING", ""});
    d.push_back({"NUM_PLANES", std::to_string(f.planes)});
    d.push_back({"NUM_SPHERES", std::to_string(f.spheres)});
    gpu::ColliderTable(scene, dragged).appendDefines(d);
    d.push_back({integratorDefine(scene.integrator.method), ""});
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Jacobi)
        d.push_back({"PRECONDITIONER_JACOBI", ""});
    if (scene.integrator.method == Method::ImplicitEuler && !scene.colliders.empty())
        d.push_back({"HAS_SOLVE_CONTACTS", ""});
    if (scene.integrator.method == Method::ImplicitEuler &&
        scene.integrator.preconditioner == Preconditioner::Multigrid)
        appendMultigridDefines(d, scene.cloth.nu, scene.cloth.nv);
    d.push_back({"WX", std::to_string(wg.x)});
    d.push_back({"WY", std::to_string(wg.y)});
    const auto [count, rows] = springTable(scene);
    d.push_back({"NUM_SPRING_OFFSETS", std::to_string(count)});
    if (count > 0) d.push_back({"SPRING_OFFSETS", rows});
    return d;
}

const char* kernelFile(Kernel k) {
    static constexpr const char* kFiles[kKernelCount] = {"compute/forces.comp",
                                                         "compute/integrate.comp",
                                                         "compute/verlet_drift.comp",
                                                         "compute/verlet_kick.comp",
                                                         "compute/rk4_stage.comp",
                                                         "compute/cg_right_hand_side.comp",
                                                         "compute/cg_warm_start.comp",
                                                         "compute/cg_start.comp",
                                                         "compute/cg_product.comp",
                                                         "compute/cg_reduce.comp",
                                                         "compute/cg_update.comp",
                                                         "compute/cg_direction.comp",
                                                         "compute/implicit_finish.comp",
                                                         "compute/vbd_start.comp",
                                                         "compute/vbd_guess.comp",
                                                         "compute/vbd_sweep.comp",
                                                         "compute/vbd_accelerate.comp",
                                                         "compute/vbd_finish.comp",
                                                         "compute/many_steps.comp",
                                                         "compute/cg_preconditioned.comp",
                                                         "compute/mg_fine.comp",
                                                         "compute/mg_galerkin.comp",
                                                         "compute/mg_lines.comp",
                                                         "compute/mg_line_transfers.comp",
                                                         "compute/mg_coarsest_factor.comp",
                                                         "compute/mg_begin.comp",
                                                         "compute/mg_relax_right_hand_side.comp",
                                                         "compute/mg_relax.comp",
                                                         "compute/mg_residual.comp",
                                                         "compute/mg_restrict.comp",
                                                         "compute/mg_prolong.comp",
                                                         "compute/mg_coarsest_solve.comp",
                                                         "compute/self_begin.comp",
                                                         "compute/self_substep.comp",
                                                         "compute/self_boxes.comp",
                                                         "compute/self_count.comp",
                                                         "compute/self_scan_blocks.comp",
                                                         "compute/self_scan_sums.comp",
                                                         "compute/self_scan_add.comp",
                                                         "compute/self_scatter.comp",
                                                         "compute/self_contacts.comp",
                                                         "compute/self_apply.comp",
                                                         "compute/self_finish.comp",
                                                         "compute/cg_contact_start.comp",
                                                         "compute/cg_grip.comp",
                                                         "compute/step_check.comp",
                                                         "compute/vbd_translation_sum.comp",
                                                         "compute/vbd_translation_solve.comp",
                                                         "compute/vbd_translation_apply.comp",
                                                         "compute/vbd_blocks.comp"};
    return kFiles[int(k)];
}

std::vector<Kernel> selfCollisionKernels() {
    std::vector<Kernel> kernels;
    for (int k = int(Kernel::SelfBegin); k <= int(Kernel::SelfFinish); ++k)
        kernels.push_back(Kernel(k));
    return kernels;
}

std::vector<Kernel> kernelsOf(Method m, Preconditioner p, bool contacts) {
    if (m == Method::ImplicitEuler && contacts) {
        std::vector<Kernel> kernels = kernelsOf(m, p);
        kernels.push_back(Kernel::CgContactStart);
        kernels.push_back(Kernel::CgGrip);
        return kernels;
    }
    if (m == Method::ImplicitEuler && p == Preconditioner::Multigrid) {
        std::vector<Kernel> kernels = kernelsOf(m);
        for (int k = int(Kernel::CgPreconditioned); k <= int(Kernel::MgCoarsestSolve); ++k)
            kernels.push_back(Kernel(k));
        return kernels;
    }
    switch (m) {
        case Method::ExplicitEuler:
        case Method::SymplecticEuler:
            return {Kernel::Forces, Kernel::Integrate};
        case Method::Verlet:
            return {Kernel::Forces, Kernel::VerletDrift, Kernel::VerletKick};
        case Method::Rk4:
            return {Kernel::Forces, Kernel::Rk4Stage};
        case Method::ImplicitEuler:
            return {Kernel::Forces,   Kernel::CgRightHandSide, Kernel::CgWarmStart,
                    Kernel::CgStart,  Kernel::CgProduct,       Kernel::CgReduce,
                    Kernel::CgUpdate, Kernel::CgDirection,     Kernel::ImplicitFinish};
        case Method::Vbd:
            return {Kernel::VbdStart,
                    Kernel::VbdGuess,
                    Kernel::VbdSweep,
                    Kernel::VbdAccelerate,
                    Kernel::VbdFinish,
                    Kernel::VbdTranslationSum,
                    Kernel::VbdTranslationSolve,
                    Kernel::VbdTranslationApply,
                    Kernel::VbdBlocks};
    }
    return {};
}

bool usesManySteps(StepDispatch dispatch, Method method, long long vertices, bool software) {
    const bool euler = method == Method::ExplicitEuler || method == Method::SymplecticEuler;
    if (dispatch == StepDispatch::ManySteps && !euler)
        throw InputError("", "dispatch",
                         std::string("many steps per dispatch exist for explicit_euler and "
                                     "symplectic_euler only, not ") +
                             methodName(method));
    if (dispatch == StepDispatch::Auto) return euler && vertices <= manyStepsMaxVertices(software);
    return dispatch == StepDispatch::ManySteps;
}

std::size_t tileBytes(WorkGroup wg) {
    return std::size_t(wg.x + 2 * kTileHalo) * std::size_t(wg.y + 2 * kTileHalo) * 16;
}

void checkTileFits(WorkGroup wg, const GpuInfo& info) {
    const std::size_t bytes = tileBytes(wg);
    if (bytes <= std::size_t(info.maxSharedMemory)) return;
    throw InputError("", "forces",
                     "the tiled forces pass with " + std::to_string(wg.x) + "x" +
                         std::to_string(wg.y) + " work groups needs " + std::to_string(bytes) +
                         " bytes of shared memory; the device allows " +
                         std::to_string(info.maxSharedMemory) + " per work group");
}

int manyStepsGroupSize(long long vertices, const GpuInfo& info) {
    const long long most = info.software ? kManyStepsGroupSoftware : info.maxInvocations;
    const long long wanted = std::min<long long>(most, (vertices + 31) / 32 * 32);
    return int(std::min<long long>({wanted, info.maxInvocations, info.maxWorkGroupSize[0]}));
}

ShaderSource assembleKernel(const std::string& dir, const std::string& file, const Scene& scene,
                            WorkGroup wg, const Defines& extra, const std::vector<bool>& dragged) {
    Defines d = gpuDefines(scene, wg, dragged);
    d.insert(d.end(), extra.begin(), extra.end());
    return assembleShader(dir, file, d);
}

}  // namespace cloth
