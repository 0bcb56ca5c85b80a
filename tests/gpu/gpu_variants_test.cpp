// The GPU backend's speed variants (docs/performance.md) change how the work is dispatched, never
// the physics: the shared-memory tile, every work-group shape and many steps per dispatch give the
// plain per-step pass's state bit for bit, the instability flag stops a many-steps run at the
// same step, and the buffers hold a 4096² cloth within 100 bytes per vertex.
#include <nlohmann/json.hpp>

#include "gpu/gpu_solver.h"
#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "model/errors.h"
#include "support/process.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

// Every runtime input of the kernels: the three families, wind, a sphere the cloth falls onto
// and a plane, pins (one given from the end), non-square and not a multiple of any shape tried.
Scene everythingScene(const char* method, int nu = 37, int nv = 23) {
    Json j = Json::parse(R"({
      "name": "gpu-variants",
      "cloth": { "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1], [5, 3]],
      "colliders": [ { "type": "sphere", "center": [0.05, 0.9, 0.0], "radius": 0.3 },
                     { "type": "plane", "point": [0, 0.75, 0], "normal": [0, 1, 0] } ],
      "wind": { "direction": [1, 0.2, 0.6], "strength": 2.0 }
    })");
    j["cloth"]["resolution"] = {nu, nv};
    j["integrator"] = {{"method", method}, {"dt", 0.001}};
    return parseScene(j.dump(), std::string("gpu variants: ") + method);
}

GpuOptions options(int wx, int wy, ForcesKernel forces, StepDispatch dispatch,
                   int checkEvery = 64) {
    return {wx, wy, checkEvery, forces, dispatch};
}

// The state after `steps`, run as two calls so that global step numbers carry across calls.
SimState run(const Scene& scene, const GpuOptions& o, long steps) {
    std::unique_ptr<Solver> gpu = makeGpuSolver(scene, o);
    for (long part : {steps / 3, steps - steps / 3}) {
        const StepResult r = gpu->step(part);
        EXPECT_FALSE(r.unstable) << gpu->name() << ": " << r.reason;
    }
    return gpu->read();
}

void expectSameState(const SimState& a, const SimState& b, const std::string& what) {
    ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
    long differing = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k)
        differing += a.positions[k] != b.positions[k] || a.velocities[k] != b.velocities[k];
    EXPECT_EQ(differing, 0) << what << ": vertices whose float state differs";
}

class GpuVariants : public GpuTest {};

// Tiled forces == global forces, bit for bit: the tile holds the same floats and the gather does
// the same arithmetic on them; every shape tried gives the same state too (a vertex's force
// does not depend on which work group computes it).
TEST_F(GpuVariants, TiledForcesAndEveryWorkGroupShapeGiveTheSameStateBitForBit) {
    const Scene s = everythingScene("explicit_euler");
    const SimState plain =
        run(s, options(16, 16, ForcesKernel::Global, StepDispatch::PerStep), 300);
    for (const auto& [wx, wy] : std::vector<std::pair<int, int>>{{16, 16}, {8, 8}, {32, 8}, {5, 3}})
        for (ForcesKernel f : {ForcesKernel::Global, ForcesKernel::Tiled}) {
            const std::string what = std::to_string(wx) + "x" + std::to_string(wy) + " " +
                                     forcesKernelName(f) + " forces";
            expectSameState(run(s, options(wx, wy, f, StepDispatch::PerStep), 300), plain, what);
        }
}

// Many steps per dispatch == one dispatch per pass, over chunks of 64, 7 and 1 steps per
// dispatch (checkEvery), with pins, both colliders (the cloth reaches the sphere) and wind, for
// both integrators it exists for.
TEST_F(GpuVariants, ManyStepsPerDispatchGiveThePerStepStateBitForBit) {
    for (const char* method : {"explicit_euler", "symplectic_euler"}) {
        const Scene s = everythingScene(method);
        const SimState perStep =
            run(s, options(16, 16, ForcesKernel::Global, StepDispatch::PerStep), 400);
        for (int every : {64, 7, 1})
            expectSameState(
                run(s, options(16, 16, ForcesKernel::Global, StepDispatch::ManySteps, every), 400),
                perStep,
                std::string(method) + ", many steps, " + std::to_string(every) + " a dispatch");
    }
}

// DESIGN.md §2 "Instability" with the flag read every 1000 steps inside 64-step dispatches:
// the same first bad step as reading it after every step, and the state frozen right after it.
TEST_F(GpuVariants, InstabilityIsReportedAtTheSameStepWithRareReadBacks) {
    Scene s = everythingScene("explicit_euler", 12, 9);
    s.integrator.dt = 0.02;  // far beyond μ/λ_max: blows up within a few hundred steps
    auto everyStep =
        makeGpuSolver(s, options(8, 8, ForcesKernel::Global, StepDispatch::PerStep, 1));
    const StepResult expected = everyStep->step(5000);
    ASSERT_TRUE(expected.unstable);
    ASSERT_EQ(expected.firstBadStep, expected.lastBadStep);
    for (StepDispatch d : {StepDispatch::PerStep, StepDispatch::ManySteps}) {
        auto rare = makeGpuSolver(s, options(8, 8, ForcesKernel::Global, d, 1000));
        const StepResult r = rare->step(5000);
        ASSERT_TRUE(r.unstable) << stepDispatchName(d);
        EXPECT_EQ(r.firstBadStep, expected.firstBadStep) << stepDispatchName(d);
        EXPECT_EQ(r.lastBadStep, expected.firstBadStep) << stepDispatchName(d);
        EXPECT_EQ(r.reason, expected.reason) << stepDispatchName(d);
        EXPECT_EQ(rare->stepsDone(), expected.firstBadStep);
        expectSameState(rare->read(), everyStep->read(), stepDispatchName(d));
    }
    // The vertex named is the lowest that went bad, the one the CPU names at the same step.
    const StepResult cpu = makeCpuSolver(s, {Precision::Float, 1})->step(5000);
    ASSERT_TRUE(cpu.unstable);
    std::printf("gpu: step %ld, %s\ncpu: step %ld, %s\n", expected.firstBadStep,
                expected.reason.c_str(), cpu.firstBadStep, cpu.reason.c_str());
    if (cpu.firstBadStep == expected.firstBadStep) {
        const auto vertex = [](const std::string& r) { return r.substr(r.rfind("vertex")); };
        EXPECT_EQ(vertex(expected.reason), vertex(cpu.reason));
    }
}

// Auto picks many steps for small explicit/symplectic Euler grids only; forcing it on another
// integrator is an input error naming the option.
TEST_F(GpuVariants, AutoDispatchPicksManyStepsForSmallEulerGridsOnly) {
    const auto manySteps = [](const Scene& s, StepDispatch d) {
        auto solver = makeGpuSolver(s, options(16, 16, ForcesKernel::Global, d));
        return dynamic_cast<const GpuSolver&>(*solver).manySteps();
    };
    EXPECT_TRUE(manySteps(everythingScene("explicit_euler", 8, 8), StepDispatch::Auto));
    EXPECT_FALSE(manySteps(everythingScene("explicit_euler", 200, 150), StepDispatch::Auto));
    EXPECT_FALSE(manySteps(everythingScene("explicit_euler", 8, 8), StepDispatch::PerStep));
    EXPECT_FALSE(manySteps(everythingScene("rk4", 8, 8), StepDispatch::Auto));
    EXPECT_THROW(manySteps(everythingScene("rk4", 8, 8), StepDispatch::ManySteps), InputError);
}

GpuInfo deviceWith(long long maxStorageBlockSize, int maxSharedMemory) {
    GpuInfo info;
    info.maxWorkGroupCount = {65535, 65535, 65535};
    info.maxWorkGroupSize = {1024, 1024, 64};
    info.maxInvocations = 1024;
    info.maxSharedMemory = maxSharedMemory;
    info.maxStorageBlockSize = maxStorageBlockSize;
    info.renderer = "test device";
    return info;
}

// Memory per vertex: the GPU holds 4096² within 100 bytes per vertex (state + forces + normals;
// the grid needs no index buffer). What it allocates is 4 vec4 per vertex plus a few tables
// that do not grow with the grid, measured on two grids and extrapolated; a device whose SSBOs
// are too small for 4096² refuses it naming that limit, before allocating.
TEST_F(GpuVariants, FourThousandSquaredFitsInOneHundredBytesPerVertex) {
    const auto bytes = [](int side) {
        auto solver = makeGpuSolver(everythingScene("explicit_euler", side, side));
        return double(dynamic_cast<const GpuSolver&>(*solver).bufferBytes());
    };
    const double small = bytes(64), large = bytes(256);
    const double perVertex = (large - small) / (256.0 * 256 - 64.0 * 64);
    EXPECT_EQ(perVertex, 64.0) << "positions, velocities, forces, normals: one vec4 each";
    const double fixed = small - 64.0 * 64 * 64;
    const double n4096 = 4096.0 * 4096;
    const double at4096 = (fixed + perVertex * n4096) / n4096;
    std::printf("GPU bytes per vertex: %.1f at 64², %.2f at 256², %.4f at 4096²\n",
                small / (64.0 * 64), large / (256.0 * 256), at4096);
    EXPECT_LE(at4096, 100.0);

    const Scene big = everythingScene("explicit_euler", 4096, 4096);
    EXPECT_NO_THROW(checkGridFits(big, {16, 16}, deviceWith(1LL << 31, 49152)));
    try {
        checkGridFits(big, {16, 16}, deviceWith(1LL << 27, 32768));  // llvmpipe's 128 MiB
        ADD_FAILURE() << "4096² fits in 128 MiB SSBOs?";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("bytes per SSBO"), std::string::npos) << e.what();
    }
    // bench speed refuses such a size up front with that reason, instead of failing mid-run.
    if (GlContext::instance().info().maxStorageBlockSize >= (1LL << 28)) return;
    const ProcessResult r = runProcess(
        {CLOTH_EXE, "bench", "speed", "--backend", "gpu", "--sizes", "4096", "--quick"}, 120);
    EXPECT_EQ(r.exitCode, 2) << describe(r);
    EXPECT_NE(r.err.find("--sizes"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bytes per SSBO"), std::string::npos) << r.err;
}

// Buffers of two vec4 a vertex must fit one binding as the vertex buffers do: on a device whose
// limit is exactly the grid's vertex buffer, the grid runs, block-Jacobi's inverses and the step
// control's kept state are refused naming their keys, and without them nothing is.
TEST(GpuVariantLimits, TwoVec4AVertexBuffersAreRefusedPastOneBindingNamingTheirKeys) {
    const int nu = 300, nv = 200;
    const GpuInfo device = deviceWith(16LL * nu * nv, 32768);
    const auto refusal = [&](Scene s) -> std::string {
        try {
            checkSceneFits(s, {16, 16}, device);
        } catch (const InputError& e) {
            return e.key() + ": " + e.reason();
        }
        return "";
    };
    Scene plain = everythingScene("implicit_euler", nu, nv);
    plain.integrator.preconditioner = Preconditioner::None;
    EXPECT_EQ(refusal(plain), "");
    Scene jacobi = plain;
    jacobi.integrator.preconditioner = Preconditioner::Jacobi;
    EXPECT_NE(refusal(jacobi).find("integrator.preconditioner: \"jacobi\"'s inverse blocks"),
              std::string::npos)
        << refusal(jacobi);
    Scene controlled = plain;
    controlled.integrator.maxStepStrain = 0.1;
    const std::string why = refusal(controlled);
    EXPECT_NE(why.find("integrator.max_step_strain: the step control's"), std::string::npos) << why;
    EXPECT_NE(why.find(std::to_string(16LL * (2 * nu * nv + 19 * 13)) + "-byte buffer"),
              std::string::npos)
        << why;  // two vec4 a vertex and one for each of the 19 x 13 work groups
    EXPECT_NE(why.find("allows at most " + std::to_string(16LL * nu * nv)), std::string::npos)
        << why;
}

// The tile of a shape and its 2-vertex halo must fit the device's shared memory.
TEST(GpuVariantLimits, TileLargerThanSharedMemoryIsRefusedNamingTheLimit) {
    EXPECT_EQ(tileBytes({16, 16}), 20u * 20u * 16u);
    EXPECT_NO_THROW(checkTileFits({16, 16}, deviceWith(1LL << 27, 32768)));
    EXPECT_THROW(checkTileFits({64, 16}, deviceWith(1LL << 27, 16384)), InputError);
    EXPECT_EQ(manyStepsGroupSize(10, deviceWith(1LL << 27, 32768)), 32);
    EXPECT_EQ(manyStepsGroupSize(1 << 20, deviceWith(1LL << 27, 32768)), 1024);
}

}  // namespace
}  // namespace cloth::test
