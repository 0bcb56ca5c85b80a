// The CPU backend's row kernels (cpu/cpu_rows.h) against its vertex-by-vertex path: every
// instruction set, both precisions, every integrator, borders and interiors, with and without
// wind, pins and colliders, must give the same bits, and so must any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <tuple>

#include "bench/bench_speed_model.h"
#include "cpu/cpu_backend.h"
#include "cpu/cpu_solver.h"
#include "model/errors.h"
#include "model/machine_memory.h"
#include "scene/scene_loader.h"
#include "support/integrator_scenes.h"
#include "support/same_bits.h"
#include "support/sanitized.h"

namespace cloth {
namespace {

using test::expectSameBits;

// everythingScene (springs of all families, wind, pins, a plane and a sphere) resized; `plain`
// drops wind, colliders and pins, `families` keeps only the spring families whose bit is set.
Scene sized(Method method, int nu, int nv, bool plain, int families = 7) {
    Scene s = everythingScene(method, 1e-3);
    s.cloth.nu = nu;
    s.cloth.nv = nv;
    s.pins = {{0, nv - 1}, {nu - 1, nv - 1}};
    if (plain) {
        s.wind.reset();
        s.colliders.clear();
        s.pins.clear();
    }
    if (!(families & 1)) s.springs.structural = 0;
    if (!(families & 2)) s.springs.shear = 0;
    if (!(families & 4)) s.springs.bend = 0;
    return s;
}

// A state off the rest shape, different at every vertex, so that every spring, normal and
// collider does something from the first step.
SimState jostled(const Scene& scene) {
    CpuSolver<double> rest(scene, 1, CpuIsa::Scalar);
    SimState s = rest.read();
    for (std::size_t k = 0; k < s.positions.size(); ++k) {
        const double a = double(k);
        s.positions[k] +=
            0.01 * glm::dvec3(std::sin(1.3 * a), std::cos(0.7 * a), std::sin(2.1 * a));
        s.velocities[k] = 0.1 * glm::dvec3(std::cos(0.3 * a), std::sin(1.1 * a), std::cos(a));
    }
    return s;
}

template <typename T>
SimState run(const Scene& scene, CpuIsa isa, int threads, long steps) {
    const SimState start = jostled(scene);
    return test::runCpu<T>(scene, isa, threads, steps, &start);
}

constexpr CpuIsa kVectorIsas[] = {CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512};
// 1×2 the seed's spring, 3×3 all border, 5×N one interior column, 17 and 33 columns shorter than
// two AVX-512 float vectors with remainders, 40×33 many interior rows.
constexpr std::pair<int, int> kGrids[] = {{1, 2}, {2, 1},  {3, 3},  {5, 9},
                                          {9, 5}, {17, 6}, {33, 7}, {40, 33}};

template <typename T>
void checkEveryIsaMatchesScalar(Method method, bool plain, int families = 7) {
    for (auto [nu, nv] : kGrids) {
        const Scene scene = sized(method, nu, nv, plain, families);
        const SimState scalar = run<T>(scene, CpuIsa::Scalar, 1, 40);
        for (CpuIsa isa : kVectorIsas) {
            if (!cpuIsaSupported(isa)) continue;
            expectSameBits(run<T>(scene, isa, 1, 40), scalar,
                           std::string(cpuIsaName(isa)) + " " + methodName(method) + " " +
                               std::to_string(nu) + "x" + std::to_string(nv) +
                               (plain ? " plain" : " wind+pins+colliders") + " families " +
                               std::to_string(families));
        }
    }
}

class RowKernels : public ::testing::TestWithParam<Method> {};

TEST_P(RowKernels, EveryInstructionSetGivesTheScalarPathsBitsInFloat) {
    checkEveryIsaMatchesScalar<float>(GetParam(), false);
    checkEveryIsaMatchesScalar<float>(GetParam(), true);
}

TEST_P(RowKernels, EveryInstructionSetGivesTheScalarPathsBitsInDouble) {
    checkEveryIsaMatchesScalar<double>(GetParam(), false);
    checkEveryIsaMatchesScalar<double>(GetParam(), true);
}

INSTANTIATE_TEST_SUITE_P(Methods, RowKernels, ::testing::ValuesIn(kMethods),
                         [](const auto& method) { return std::string(methodName(method.param)); });

// Each subset of the spring families takes its own gather kernel.
TEST(RowKernelsFamilies, EverySubsetOfSpringFamiliesGivesTheScalarPathsBits) {
    for (int families = 1; families < 8; ++families) {
        checkEveryIsaMatchesScalar<float>(Method::ExplicitEuler, false, families);
        checkEveryIsaMatchesScalar<double>(Method::SymplecticEuler, true, families);
    }
}

// The fused Euler sweep (forces of a row used at once, new positions into a second buffer)
// against the scalar path's two passes (all forces, a barrier, then the update in place).
TEST(FusedSweep, EqualsTheTwoPassUpdateBitForBit) {
    for (Method m : {Method::ExplicitEuler, Method::SymplecticEuler}) {
        const Scene scene = sized(m, 64, 48, false);
        CpuSolver<double> fused(scene, 1), twoPass(scene, 1, CpuIsa::Scalar);
        fused.write(jostled(scene));
        twoPass.write(jostled(scene));
        for (int call = 0; call < 5; ++call) {  // several step() calls: the buffers swap
            fused.step(7);
            twoPass.step(7);
            expectSameBits(fused.read(), twoPass.read(), methodName(m));
        }
    }
}

// docs/colliders.md's shapes, thickness, friction and motion, all touching the cloth from the
// first step: the row loops with their vectorised "can this row touch it?" test give the
// vertex-by-vertex path's bits on every instruction set, and the poses taken in the barrier's
// completion give the serial bits for any thread count.
Scene withEveryColliderKind(Method m) {
    Scene s = sized(m, 70, 50, false);
    const Scene c = parseScene(R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
      "integrator": {"dt": 0.001}, "colliders": [
      { "type": "box", "center": [0, 1.0, 0], "half_extents": [0.3, 0.05, 0.3],
        "rotation": { "axis": [1, 0, 1], "degrees": 10 }, "thickness": 0.01, "friction": 0.5,
        "motion": { "type": "linear", "velocity": [0.2, 1, 0] } },
      { "type": "capsule", "a": [-0.5, 1.05, 0.5], "b": [0.5, 1.0, 0.5], "radius": 0.06,
        "friction": 0.3, "motion": { "type": "rotation", "axis": [0, 1, 0],
        "pivot": [0, 0, 0.2], "degrees_per_second": 120 } },
      { "type": "sphere", "center": [0.3, 1.1, -0.4], "radius": 0.15, "friction": 1.0,
        "motion": { "type": "oscillation", "axis": [0, 1, 0], "amplitude": 0.1,
                    "frequency": 3 } },
      { "type": "plane", "point": [0, 0.98, 0], "normal": [0, 1, 0.1], "thickness": 0.01 } ]})",
                               "every collider kind (test)");
    s.colliders = c.colliders;
    return s;
}

TEST(RowColliders, EveryKindGivesTheScalarPathsBitsOnEveryIsaAndThreadCount) {
    const long steps = test::sanitizedSteps(40, 10);
    for (Method m : kMethods) {
        const Scene scene = withEveryColliderKind(m);
        const SimState f = run<float>(scene, CpuIsa::Scalar, 1, steps);
        const SimState d = run<double>(scene, CpuIsa::Scalar, 1, steps);
        Scene free = scene;
        free.colliders.clear();
        const SimState none = run<double>(free, CpuIsa::Scalar, 1, steps);
        int touched = 0;  // vertices the colliders moved: they act from the start
        for (std::size_t k = 0; k < d.positions.size(); ++k)
            touched += glm::length(d.positions[k] - none.positions[k]) > 1e-3;
        EXPECT_GT(touched, 100) << methodName(m);
        for (CpuIsa isa : {CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512, CpuIsa::Scalar}) {
            if (!cpuIsaSupported(isa)) continue;
            for (int t : {1, 3}) {
                const std::string what = std::string(methodName(m)) + " " + cpuIsaName(isa) + " " +
                                         std::to_string(t) + " threads";
                expectSameBits(run<float>(scene, isa, t, steps), f, what + " float");
                expectSameBits(run<double>(scene, isa, t, steps), d, what + " double");
            }
        }
    }
}

// A grid that passes the loader's coarse check (160 B a vertex) but whose integrator's arrays
// would not fit: implicit Euler in double with colliders holds 369 B a vertex. makeCpuSolver
// refuses it, naming cloth.resolution, before allocating anything.
TEST(CpuMemory, AGridWhoseArraysExceedTheMemoryIsRefusedBeforeAllocating) {
    const int side = int(std::sqrt(physicalMemoryBytes() / 300));
    const std::string text =
        R"({"cloth": {"resolution": [)" + std::to_string(side) + ", " + std::to_string(side) +
        R"(], "size": [1, 1]}, "integrator": {"method": "implicit_euler", "dt": 0.001},
            "colliders": [{"type": "plane", "point": [0, -5, 0], "normal": [0, 1, 0]}]})";
    const Scene scene = parseScene(text, "big (test)");
    try {
        makeCpuSolver(scene, {Precision::Double, 1});
        ADD_FAILURE() << side << "² was not refused";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "cloth.resolution") << e.what();
        std::printf("%s\n", e.what());
    }
}

// Bands of whole rows split the grid mid-way (70 columns: 14-row chunks; 3 threads split 50
// rows as 14/14/22, 2 as 28/22): every thread count gives the serial bits, on every path.
TEST(RowBands, ThreadCountsOneTwoThreeGiveTheSameBits) {
    for (Method m : kMethods)
        for (CpuIsa isa : {CpuIsa::Scalar, CpuIsa::Auto}) {
            const Scene scene = sized(m, 70, 50, false);
            const SimState one = run<float>(scene, isa, 1, 25);
            for (int t : {2, 3})
                expectSameBits(run<float>(scene, isa, t, 25), one,
                               std::string(methodName(m)) + " " + cpuIsaName(isa) + " " +
                                   std::to_string(t) + " threads");
        }
}

// bench speed reports app::cpuBytesPerVertex as the CPU's memory: it must be what the solver
// holds, for every integrator and precision, with frictionless colliders and with friction, and
// with vbd's translation sweeps and levels; the threads' scratch rows stay O(side).
TEST(CpuMemory, BytesPerVertexOfTheBenchModelAreWhatTheSolverAllocates) {
    for (Method m : kMethods)
        for (double rub : {0.0, 0.5})
            for (int sweeps : {0, 2}) {
                Scene scene = sized(m, 64, 40, false);
                ASSERT_FALSE(scene.colliders.empty());
                scene.colliders[0].friction = rub;
                scene.integrator.translationSweeps = sweeps;
                scene.integrator.translationLevels = sweeps > 0 ? 4 : 0;
                CpuSolver<float> f(scene, 2);
                CpuSolver<double> d(scene, 2);
                const Preconditioner p = scene.integrator.preconditioner;
                const bool colliders = !scene.colliders.empty(), friction = scene.anyFriction();
                const bool kernels = f.isa() != CpuIsa::Scalar;
                const bool translation = scene.integrator.vbdTranslates();
                EXPECT_EQ(f.allocatedBytes(),
                          64 * 40 *
                              app::cpuBytesPerVertex(Precision::Float, m, p, colliders, kernels,
                                                     friction, translation))
                    << methodName(m) << " " << sweeps;
                EXPECT_EQ(d.allocatedBytes(),
                          64 * 40 *
                              app::cpuBytesPerVertex(Precision::Double, m, p, colliders, kernels,
                                                     friction, translation))
                    << methodName(m) << " " << sweeps;
                EXPECT_LE(d.scratchBytes(), 2 * (3 * 6 + 3) * 64 * sizeof(double)) << methodName(m);
            }
}

TEST(CpuIsaChoice, AutoIsTheWidestSupportedAndAnUnknownNameIsNone) {
    const CpuIsa best = resolveCpuIsa(CpuIsa::Auto);
    EXPECT_TRUE(cpuIsaSupported(best));
    if (cpuIsaSupported(CpuIsa::Avx512)) {
        EXPECT_EQ(best, CpuIsa::Avx512);
    }
    EXPECT_EQ(resolveCpuIsa(CpuIsa::Scalar), CpuIsa::Scalar);
    EXPECT_TRUE(cpuIsaSupported(CpuIsa::Generic));

    // Names round-trip; a mistyped one is no set (the app refuses it: tests/app/environment_test).
    for (CpuIsa isa : {CpuIsa::Auto, CpuIsa::Scalar, CpuIsa::Generic, CpuIsa::Avx2, CpuIsa::Avx512})
        EXPECT_EQ(cpuIsaFromName(cpuIsaName(isa)), isa);
    EXPECT_FALSE(cpuIsaFromName("avx-512").has_value());
}

}  // namespace
}  // namespace cloth
