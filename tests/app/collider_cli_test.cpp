// Collider input through the command line (docs/colliders.md §5): bad values exit with 2 naming
// the file and the key; good ones validate (and are described) and run on the CPU and on the GPU
// (docs/colliders.md §9).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
const std::string kExe = CLOTH_EXE;

// A small scene with one collider `collider` (JSON), written into its own folder as scene.json.
fs::path writeScene(const std::string& name, const std::string& collider) {
    const fs::path dir = test::freshTempDir("ColliderCli", name);
    std::ofstream(dir / "scene.json") << R"({
      "cloth": { "resolution": [6, 5], "size": [0.5, 0.4], "origin": [-0.25, 1, -0.2] },
      "springs": { "structural": 100 }, "damping": 0.5,
      "integrator": { "dt": 0.001 }, "duration": 0.02,
      "colliders": [ )" + collider + R"( ]
    })";
    return dir / "scene.json";
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

void expectExit2Naming(const fs::path& scene, const std::string& key) {
    for (const char* cmd : {"validate", "run"}) {
        const auto r = test::runProcess({kExe, cmd, scene.string()}, 60);
        EXPECT_EQ(r.exitCode, 2) << cmd << "\n" << test::describe(r);
        EXPECT_TRUE(has(r.err, scene.string())) << cmd << ": file not named\n" << r.err;
        EXPECT_TRUE(has(r.err, key)) << cmd << ": key " << key << " not named\n" << r.err;
    }
}

TEST(ColliderCli, NegativeRadiusExitsTwoNamingTheKey) {
    expectExit2Naming(writeScene("negative_radius",
                                 R"({"type": "capsule", "a": [0, 0, 0], "b": [0, 1, 0],
                                     "radius": -0.1})"),
                      "colliders[0].radius");
}

TEST(ColliderCli, MissingMeshFileExitsTwoNamingTheKey) {
    expectExit2Naming(writeScene("missing_mesh", R"({"type": "mesh", "file": "nowhere.obj",
                                                     "cell": 0.05, "band": 0.1})"),
                      "colliders[0].file");
}

TEST(ColliderCli, EmptyObjExitsTwoNamingTheKey) {
    const fs::path scene = writeScene(
        "empty_obj", R"({"type": "mesh", "file": "empty.obj", "cell": 0.05, "band": 0.1})");
    std::ofstream(scene.parent_path() / "empty.obj") << "";
    expectExit2Naming(scene, "colliders[0].file");
}

// JSON has no NaN: a number too large for a double (read as infinite) or a zero axis stands for
// a rotation that is no rotation.
TEST(ColliderCli, NonFiniteOrZeroRotationAxisExitsTwoNamingTheKey) {
    expectExit2Naming(writeScene("inf_axis", R"({"type": "box", "center": [0, 0, 0],
                                                 "half_extents": [1, 0.1, 1],
                                                 "rotation": {"axis": [1e999, 0, 0],
                                                              "degrees": 10}})"),
                      "colliders[0].rotation.axis");
    expectExit2Naming(writeScene("zero_axis", R"({"type": "box", "center": [0, 0, 0],
                                                  "half_extents": [1, 0.1, 1],
                                                  "rotation": {"axis": [0, 0, 0],
                                                               "degrees": 10}})"),
                      "colliders[0].rotation.axis");
}

// `run --backend gpu` on `scene`: exit 0, or 4 where no GPU context can be made (skipped then,
// unless CLOTH_REQUIRE_GPU=1, DESIGN.md §6).
void expectGpuRuns(const fs::path& scene) {
    const auto r =
        test::runProcess({kExe, "run", scene.string(), "--backend", "gpu", "--quiet"}, 60);
    const char* required = std::getenv("CLOTH_REQUIRE_GPU");
    if (r.exitCode == 4 && !(required && std::string(required) == "1"))
        GTEST_SKIP() << "no GPU: " << r.err;
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
}

// validate describes the new keys; run simulates them on both backends.
TEST(ColliderCli, BoxValidatesAndRunsOnBothBackends) {
    const fs::path scene = writeScene("box", R"({"type": "box", "center": [0, 0.9, 0],
        "half_extents": [0.5, 0.05, 0.5], "rotation": {"axis": [1, 0, 0], "degrees": 5},
        "thickness": 0.01, "friction": 0.5})");
    auto r = test::runProcess({kExe, "validate", scene.string()}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(has(r.out, "box at")) << r.out;
    EXPECT_TRUE(has(r.out, "friction 0.5")) << r.out;
    r = test::runProcess({kExe, "run", scene.string(), "--backend", "cpu", "--quiet"}, 60);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    expectGpuRuns(scene);
}

TEST(ColliderCli, GpuRunsAMovingSphereWithFriction) {
    expectGpuRuns(writeScene("sphere_friction", R"({"type": "sphere", "center": [0, 0.5, 0],
        "radius": 0.3, "friction": 0.2,
        "motion": {"type": "linear", "velocity": [0, 0.5, 0]}})"));
}

// docs/colliders.md §7's rule through --set, for run and validate alike: the windsock's pole
// (r + h = 3 cm) swings at up to 0.47 m/s, so Δt = 0.07 s, or a 100 Hz swing at its Δt, lets it
// outrun the tunnelling limit: exit 2 naming the scene, colliders[0].motion, and the Δt that
// would pass.
TEST(ColliderCli, SetThatOutrunsTheTunnellingLimitExitsTwo) {
    const std::string scene = CLOTH_SOURCE_DIR "/scenes/windsock.json";
    for (const char* set : {"integrator.dt=0.07", "colliders[0].motion.frequency=100"}) {
        for (const char* cmd : {"validate", "run"}) {
            const auto r = test::runProcess({kExe, cmd, scene, "--set", set}, 60);
            EXPECT_EQ(r.exitCode, 2) << cmd << " --set " << set << "\n" << test::describe(r);
            EXPECT_TRUE(has(r.err, scene)) << r.err;
            EXPECT_TRUE(has(r.err, "colliders[0].motion")) << r.err;
            EXPECT_TRUE(has(r.err, "it passes with integrator.dt ≤")) << r.err;
        }
    }
    const auto ok = test::runProcess({kExe, "validate", scene, "--set", "integrator.dt=0.06"}, 60);
    EXPECT_EQ(ok.exitCode, 0) << "0.47 m/s × 0.06 s < 3 cm\n" << test::describe(ok);
}

}  // namespace
}  // namespace cloth
