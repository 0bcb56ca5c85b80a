// What goes wrong reaches the user clearly (STYLE.md "Errors"): a missing shader directory, a
// shader that does not compile (file and line), a bad work-group override, a grid the device
// cannot hold; and an unstable run stops at the step the CPU also finds (DESIGN.md §2).
#include <filesystem>
#include <fstream>

#include "cpu/cpu_backend.h"
#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "model/errors.h"

namespace cloth::test {
namespace {

namespace fs = std::filesystem;

Scene smallScene(int nu = 6, int nv = 4) {
    Scene s = parseScene(R"({
      "name": "small",
      "cloth": { "resolution": [6, 4], "size": [1, 1], "origin": [0, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1] },
      "springs": { "structural": 100.0 },
      "damping": 0.5,
      "integrator": { "method": "explicit_euler", "dt": 0.001 }
    })",
                         "small (test)");
    s.cloth.nu = nu;
    s.cloth.nv = nv;
    return s;
}

template <typename E, typename F>
std::string messageOf(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an exception";
    return {};
}

class GpuErrors : public GpuTest {};

TEST_F(GpuErrors, MissingShaderDirectoryIsAClearError) {
    ScopedShaderDir dir("/nonexistent");
    const std::string m = messageOf<std::runtime_error>([] { makeGpuSolver(smallScene()); });
    EXPECT_NE(m.find("/nonexistent"), std::string::npos) << m;
    EXPECT_NE(m.find("CLOTH_SHADER_DIR"), std::string::npos) << m;
}

// A copy of shaders/ with one line broken in an included file: the message names that file
// and line, not the assembled source's.
TEST_F(GpuErrors, CompileErrorNamesTheIncludedFileAndLine) {
    const fs::path dir =
        fs::temp_directory_path() / ("cloth_shaders_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::copy(CLOTH_SOURCE_DIR "/shaders", dir, fs::copy_options::recursive);
    {
        std::ofstream out(dir / "compute" / "common.glsl", std::ios::app);
        out << "\nfloat broken() { return undeclaredThing; }\n";
    }
    std::ifstream in(dir / "compute" / "common.glsl");
    int lines = 0;
    for (std::string l; std::getline(in, l);) ++lines;
    ScopedShaderDir env(dir.string());
    const std::string m = messageOf<std::runtime_error>([] { makeGpuSolver(smallScene()); });
    const std::string where =
        (dir / "compute" / "common.glsl").string() + ":" + std::to_string(lines);
    EXPECT_NE(m.find(where), std::string::npos) << "expected " << where << " in:\n" << m;
    std::printf("%s", m.c_str());
    EXPECT_NE(m.find("forces.comp"), std::string::npos) << m;
    fs::remove(dir / "compute" / "layout.glsl");
    const std::string missing = messageOf<std::runtime_error>([] { makeGpuSolver(smallScene()); });
    EXPECT_NE(missing.find("layout.glsl"), std::string::npos) << missing;
    EXPECT_NE(missing.find("forces.comp:"), std::string::npos) << "the including line: " << missing;
    fs::remove_all(dir);
}

// A work group the device cannot run is refused naming where it came from (the app passes
// CLOTH_WORKGROUP's; a malformed value is the app's to refuse: tests/app/environment_test.cpp).
TEST_F(GpuErrors, BadWorkGroupOverrideNamesTheVariable) {
    for (auto [x, y] : {std::pair{64, 64}, {0, 16}, {2000, 1}}) {
        GpuOptions o;
        o.workGroupX = x;
        o.workGroupY = y;
        o.workGroupKey = "CLOTH_WORKGROUP";
        const std::string m = messageOf<InputError>([&] { makeGpuSolver(smallScene(), o); });
        EXPECT_NE(m.find("CLOTH_WORKGROUP"), std::string::npos) << x << "x" << y << ": " << m;
    }
    GpuOptions o;
    o.workGroupX = 8;
    o.workGroupY = 4;
    std::unique_ptr<Solver> solver = makeGpuSolver(smallScene(37, 53), o);
    EXPECT_NE(solver->name().find("8x4"), std::string::npos) << solver->name();
}

TEST_F(GpuErrors, ImpossibleGridIsAnInputError) {
    // 65536 rows of 1×1 work groups: one more than a dispatch may have (DESIGN.md §3).
    const std::string m = messageOf<InputError>([] {
        makeGpuSolver(smallScene(1, 65536), {1, 1});
    });
    EXPECT_NE(m.find("65536 work groups"), std::string::npos) << m;
    EXPECT_NE(m.find("cloth.resolution"), std::string::npos) << m;
    // Past the device's SSBO size (llvmpipe: 128 MiB, so 4096² vec4s do not fit); refused
    // before anything is allocated.
    const long long limit = GlContext::instance().info().maxStorageBlockSize;
    if (limit / 16 < 4096LL * 4096) {
        const std::string big =
            messageOf<InputError>([] { makeGpuSolver(smallScene(4096, 4096)); });
        EXPECT_NE(big.find("bytes per SSBO"), std::string::npos) << big;
    }
}

// The GPU computes in float: a cloth past what float can square (model/float_range.h) is refused
// naming cloth.size, where its first step went non-finite and was reported unstable.
TEST_F(GpuErrors, AClothFloatCannotSquareIsAnInputError) {
    Scene s = smallScene(4, 4);
    s.cloth.size = {1e50, 1e50};
    const std::string m = messageOf<InputError>([&] { makeGpuSolver(s); });
    EXPECT_NE(m.find("cloth.size"), std::string::npos) << m;
}

// The kernels unroll each collider: 64 build (a second), 65 are refused naming the key before any
// kernel is built, where 20,000 spheres once took minutes and 11.5 GB.
TEST_F(GpuErrors, TooManyCollidersForTheKernelsIsAnInputError) {
    Scene s = smallScene();
    s.colliders.assign(65, Collider{});
    for (std::size_t n = 0; n < s.colliders.size(); ++n)
        s.colliders[n].shape = Sphere{{0.0, -10.0 - double(n), 0.0}, 0.1};
    const std::string m = messageOf<InputError>([&] { makeGpuSolver(s); });
    EXPECT_NE(m.find("colliders: 65 colliders"), std::string::npos) << m;
    EXPECT_NE(m.find("--backend cpu"), std::string::npos) << m;
    s.colliders.resize(64);
    EXPECT_NO_THROW(makeGpuSolver(s));
}

// The multigrid preconditioner holds 25 double blocks per vertex of every grid: a grid whose
// stencils exceed one SSBO of the device is refused naming the key, before anything is allocated.
TEST_F(GpuErrors, MultigridTooLargeForTheDeviceIsAnInputError) {
    const long long limit = GlContext::instance().info().maxStorageBlockSize;
    int side = 64;
    while (multigridBytes(side, side, 1).stencil <= limit && side < 65536) side *= 2;
    Scene s = smallScene(side, side);
    s.integrator.method = Method::ImplicitEuler;
    s.integrator.preconditioner = Preconditioner::Multigrid;
    if (16LL * side * side > limit) GTEST_SKIP() << "the state does not fit first at " << side;
    const std::string m = messageOf<InputError>([&] { makeGpuSolver(s); });
    EXPECT_NE(m.find("integrator.preconditioner"), std::string::npos) << m;
    EXPECT_NE(m.find("bytes per SSBO"), std::string::npos) << m;
}

// The aggregation preconditioner has no GPU kernels: the GPU refuses it naming the key and the
// way out, before anything is built.
TEST_F(GpuErrors, AggregationPreconditionerIsRefusedNamingTheCpuBackend) {
    Scene s = smallScene(16, 16);
    s.integrator.method = Method::ImplicitEuler;
    s.integrator.preconditioner = Preconditioner::Aggregation;
    const std::string m = messageOf<InputError>([&] { makeGpuSolver(s); });
    EXPECT_NE(m.find("integrator.preconditioner"), std::string::npos) << m;
    EXPECT_NE(m.find("--backend cpu"), std::string::npos) << m;
}

// A stiff spring with a large Δt (far outside Δt < μ/λ_max) blows up within a few steps.
Scene unstableScene() {
    Scene s = loadShippedScene("spring");
    s.springs.structural = 1e5;
    s.integrator.dt = 0.01;
    return s;
}

long cpuFirstBadStep(const Scene& scene) {
    std::unique_ptr<Solver> cpu = makeCpuSolver(scene, {Precision::Float, 1});
    const StepResult r = cpu->step(1000);
    EXPECT_TRUE(r.unstable);
    return r.firstBadStep;
}

TEST_F(GpuErrors, InstabilityIsCaughtAtTheCpusStep) {
    const Scene scene = unstableScene();
    const long cpuStep = cpuFirstBadStep(scene);
    for (int checkEvery : {1, 4, 64}) {
        std::unique_ptr<Solver> gpu = makeGpuSolver(scene, {16, 16, checkEvery});
        StepResult r = gpu->step(3);  // global step numbers carry across calls
        r = r.unstable ? r : gpu->step(1000);
        ASSERT_TRUE(r.unstable) << checkEvery;
        EXPECT_LE(r.firstBadStep, cpuStep) << checkEvery;
        EXPECT_GE(r.lastBadStep, cpuStep) << checkEvery;
        EXPECT_EQ(gpu->stepsDone(), r.firstBadStep) << "the state stops at the bad step";
        EXPECT_FALSE(r.reason.empty());
        std::printf("checkEvery %2d: GPU first bad step [%ld, %ld], CPU %ld: %s\n", checkEvery,
                    r.firstBadStep, r.lastBadStep, cpuStep, r.reason.c_str());
        const StepResult again = gpu->step(10);  // stays stopped
        EXPECT_TRUE(again.unstable);
        EXPECT_EQ(again.stepsTaken, 0);
        EXPECT_EQ(gpu->stepsDone(), r.firstBadStep);
    }
}

// With max_speed out of reach the run goes on until a value overflows: caught as non-finite.
TEST_F(GpuErrors, NonFiniteValuesAreCaught) {
    Scene scene = unstableScene();
    scene.maxSpeed = 1e300;
    const long cpuStep = cpuFirstBadStep(scene);
    std::unique_ptr<Solver> gpu = makeGpuSolver(scene);
    const StepResult r = gpu->step(1000);
    ASSERT_TRUE(r.unstable);
    EXPECT_LE(r.firstBadStep, cpuStep);
    EXPECT_GE(r.lastBadStep, cpuStep);
    EXPECT_NE(r.reason.find("non-finite"), std::string::npos) << r.reason;
    std::printf("non-finite: GPU [%ld, %ld], CPU %ld: %s\n", r.firstBadStep, r.lastBadStep, cpuStep,
                r.reason.c_str());
}

}  // namespace
}  // namespace cloth::test
