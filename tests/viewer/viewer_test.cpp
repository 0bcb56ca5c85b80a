// The viewer: its session (the panel's applyParameters path, backend switches carrying the state,
// pins, grab, reset, instability) in-process, and the real window under Xvfb on both backends,
// looked at through its screenshot.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "model/errors.h"
#include "render/image_checks.h"
#include "scene/scene_loader.h"
#include "support/process.h"
#include "viewer/viewer_session.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using app::ViewerParams;
using app::ViewerSession;

const std::string kScenes = CLOTH_SOURCE_DIR "/scenes/";

Scene smallScene(const std::string& name) {
    return loadScene(kScenes + name + ".json",
                     {"cloth.resolution=[8,6]", "integrator.substeps=50"});
}

double maxDifference(const SimState& a, const SimState& b) {
    double worst = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k)
        worst = std::max(worst, glm::length(a.positions[k] - b.positions[k]));
    return worst;
}

SimState afterFrames(ViewerSession& s, int frames) {
    for (int f = 0; f < frames; ++f) s.advance();
    return s.solver().read();
}

// DESIGN.md §2's strain check in the viewer: the soft spring (K = 2 N/m, static strain 4.9) is
// stopped as unstable at the first diagnostics sample past max_strain and the panel says why;
// the stiff one of the shipped scene is not.
TEST(ViewerSession, ASpringPastMaxStrainStopsTheSession) {
    ViewerSession soft(loadScene(kScenes + "spring.json", {"springs.structural=2"}), {});
    ViewerSession stiff(loadScene(kScenes + "spring.json"), {});
    for (int frame = 0; frame < 100 && !soft.unstable(); ++frame) {
        soft.advance();
        soft.sampleDiagnostics();
        stiff.advance();
        stiff.sampleDiagnostics();
    }
    EXPECT_TRUE(soft.unstable());
    EXPECT_NE(soft.instability().find("> max_strain 1"), std::string::npos) << soft.instability();
    EXPECT_FALSE(stiff.unstable()) << stiff.instability();
}

TEST(ViewerSession, AParameterSetThroughThePanelPathChangesTheSimulation) {
    ViewerSession plain(smallScene("hanging"), {});
    ViewerSession edited(smallScene("hanging"), {});
    ViewerParams p = edited.params();
    p.scene.gravity = {0, -3, 0};
    p.scene.material->airDamping = 2;  // hanging is denim: 0.463 1/s
    const int before = edited.rebuilds();
    edited.applyParameters(p);
    EXPECT_EQ(edited.rebuilds(), before) << "gravity and air damping are taken live";
    EXPECT_EQ(edited.params().scene.gravity.y, -3);
    EXPECT_GT(maxDifference(afterFrames(plain, 10), afterFrames(edited, 10)), 1e-4);
}

TEST(ViewerSession, SwitchingAFeatureOnBuildsANewSolverAndCarriesTheState) {
    ViewerSession s(smallScene("hanging"), {});
    const SimState before = afterFrames(s, 5);
    ViewerParams p = s.params();
    p.scene.wind = Wind{{1, 0, 0}, 0.2};
    const int rebuilds = s.rebuilds();
    s.applyParameters(p);
    EXPECT_EQ(s.rebuilds(), rebuilds + 1);
    EXPECT_EQ(maxDifference(before, s.solver().read()), 0.0);
    EXPECT_TRUE(s.solver().features().wind);
    EXPECT_NEAR(s.simTime(), 5 * 50 * p.scene.integrator.dt, 1e-12);
}

// Step control wraps the backend (solver/step_control.h): switching it on builds the wrapped
// solver, carrying the state; its limit then changes live.
TEST(ViewerSession, SwitchingStepControlOnBuildsANewSolverAndItsLimitIsLive) {
    ViewerSession s(smallScene("hanging"), {});
    const SimState before = afterFrames(s, 5);
    ViewerParams p = s.params();
    p.scene.integrator.maxStepStrain = 0.1;
    const int rebuilds = s.rebuilds();
    s.applyParameters(p);
    EXPECT_EQ(s.rebuilds(), rebuilds + 1);
    EXPECT_EQ(maxDifference(before, s.solver().read()), 0.0);
    EXPECT_TRUE(s.solver().features().stepControl);
    p.scene.integrator.maxStepStrain = 0.05;
    s.applyParameters(p);
    EXPECT_EQ(s.rebuilds(), rebuilds + 1) << "a new limit is taken live";
    afterFrames(s, 2);
    EXPECT_GE(s.solver().stepControlStats().substeps, 2 * 50);
    EXPECT_NEAR(s.simTime(), 7 * 50 * p.scene.integrator.dt, 1e-12);
}

TEST(ViewerSession, SwitchingAColliderOffRemovesItFromTheSolver) {
    ViewerSession s(smallScene("drape"), {});
    ViewerParams p = s.params();
    p.colliderOn[1] = false;  // the sphere
    s.applyParameters(p);
    EXPECT_EQ(s.solver().features().spheres, 0);
    EXPECT_EQ(s.params().scene.colliders.size(), 2u) << "kept, switched off";
}

TEST(ViewerSession, ResolutionChangeRebuildsTheClothAtRest) {
    ViewerSession s(smallScene("hanging"), {});
    afterFrames(s, 3);
    ViewerParams p = s.params();
    p.scene.cloth.nu = 12;
    p.scene.cloth.nv = 9;
    s.applyParameters(p);
    const SimState st = s.solver().read();
    EXPECT_EQ(st.nu, 12);
    EXPECT_EQ(st.nv, 9);
    EXPECT_EQ(s.totalSteps(), 0);
    ASSERT_EQ(s.params().scene.pins.size(), 2u);  // the two corners, mapped onto the new grid
    EXPECT_EQ(s.params().scene.pins[1].i, 11);
}

TEST(ViewerSession, PinsHoldAndTheGrabPulls) {
    ViewerSession s(smallScene("hanging"), {});
    const std::int64_t k = 5 * 8 + 4;  // (4, 5), a free vertex
    s.togglePin(k);
    const glm::dvec3 pinned = s.solver().read().positions[std::size_t(k)];
    afterFrames(s, 5);
    EXPECT_EQ(s.solver().read().positions[std::size_t(k)], pinned);
    s.togglePin(k);
    const std::int64_t g = 5 * 8 + 1;
    const glm::dvec3 start = s.solver().read().positions[std::size_t(g)];
    const glm::dvec3 target = start + glm::dvec3(0, 0.5, 0);
    s.grab(g, target);
    afterFrames(s, 10);
    const glm::dvec3 end = s.solver().read().positions[std::size_t(g)];
    EXPECT_LT(glm::length(end - target), glm::length(start - target));
    s.release();
    EXPECT_FALSE(s.grabbed().has_value());
}

TEST(ViewerSession, BackendSwitchCarriesTheState) {
    ViewerSession s(smallScene("hanging"), {});
    const SimState before = afterFrames(s, 4);
    s.setBackend({Backend::Cpu, Precision::Float, 1});
    EXPECT_LT(maxDifference(before, s.solver().read()), 1e-6);
    try {
        s.setBackend({Backend::Gpu, Precision::Float, 0});
    } catch (const GpuUnavailable& e) {
        if (test::gpuRequiredByEnvironment()) FAIL() << e.what();
        GTEST_SKIP() << "no GPU: " << e.what();
    }
    EXPECT_LT(maxDifference(before, s.solver().read()), 1e-6);
    afterFrames(s, 2);
    EXPECT_EQ(s.totalSteps(), 6 * 50);
}

// A box collider with thickness and friction (docs/colliders.md §9): the switch to the GPU
// carries the state and the session goes on there.
TEST(ViewerSession, BackendSwitchRunsBoxCollidersOnTheGpu) {
    ViewerSession s(
        loadScene(kScenes + "hanging.json", {"cloth.resolution=[8,6]", "integrator.substeps=50",
                                             R"(colliders=[{"type":"box","center":[0,0,0],)"
                                             R"("half_extents":[1,0.1,1],"thickness":0.01,)"
                                             R"("friction":0.5}])"}),
        {});
    const SimState before = afterFrames(s, 2);
    try {
        s.setBackend({Backend::Gpu, Precision::Float, 0});
    } catch (const GpuUnavailable& e) {
        if (test::gpuRequiredByEnvironment()) FAIL() << e.what();
        GTEST_SKIP() << "no GPU: " << e.what();
    }
    EXPECT_EQ(s.backend().backend, Backend::Gpu);
    EXPECT_LT(maxDifference(before, s.solver().read()), 1e-6);
    afterFrames(s, 1);
    EXPECT_EQ(s.totalSteps(), 3 * 50);
}

TEST(ViewerSession, InstabilityStopsTheRunUntilReset) {
    ViewerSession s(smallScene("hanging"), {});
    ViewerParams p = s.params();
    p.scene.integrator.dt = 0.01;
    s.applyParameters(p);
    for (int f = 0; f < 20 && !s.unstable(); ++f) s.advance();
    ASSERT_TRUE(s.unstable());
    EXPECT_NE(s.instability().find("unstable at step"), std::string::npos) << s.instability();
    EXPECT_EQ(s.advance(), 0);
    s.sampleDiagnostics();
    EXPECT_TRUE(s.history().energy.empty()) << "nothing non-finite is plotted";
    p.scene.integrator.dt = 2e-5;
    s.applyParameters(p);
    EXPECT_FALSE(s.unstable());
    EXPECT_EQ(s.advance(), 50);
}

// implicit_euler's solves are plotted: each diagnostics sample holds the CG iterations per step
// since the last one and log10 of the last final |r|/|b| (below log10 of the tolerance). The
// panel's preconditioner choice goes through applyParameters: on the stiff drape block-Jacobi
// converges in a few iterations per step, none then hits the cap. The other integrators plot
// nothing of the kind.
TEST(ViewerSession, ImplicitSolvesArePlottedAndThePreconditionerIsLive) {
    Scene scene = loadScene(kScenes + "drape.json",
                            {"cloth.resolution=[24,24]", "integrator.method=\"implicit_euler\"",
                             "integrator.dt=0.016667", "integrator.substeps=4",
                             "integrator.preconditioner=\"jacobi\"", "material.stretch=1e5"});
    ViewerSession s(scene, {});
    s.advance();
    s.sampleDiagnostics();
    s.advance();
    s.sampleDiagnostics();
    ASSERT_EQ(s.history().iterations.size(), 2u);
    const SolveStats& stats = s.solver().solveStats();
    EXPECT_EQ(stats.solves, 8);
    EXPECT_FLOAT_EQ(s.history().iterations[0] * 4 + s.history().iterations[1] * 4,
                    float(stats.iterations));
    EXPECT_LT(s.history().residual.back(), std::log10(scene.integrator.tolerance));
    const float jacobi = s.history().iterations.back();
    ViewerParams p = s.params();
    p.scene.integrator.preconditioner = Preconditioner::None;
    s.applyParameters(p);
    s.advance();
    s.sampleDiagnostics();
    const float none = s.history().iterations.back();
    std::printf("CG iterations per step: jacobi %.1f, then none %.1f\n", jacobi, none);
    EXPECT_LT(jacobi, 30.0f);
    EXPECT_GT(none, 4 * jacobi);

    ViewerSession symplectic(smallScene("drape"), {});
    symplectic.advance();
    symplectic.sampleDiagnostics();
    EXPECT_EQ(symplectic.history().energy.size(), 1u);
    EXPECT_TRUE(symplectic.history().iterations.empty());
}

// ---- the real window, under Xvfb -----------------------------------------------------------

std::string xvfbRun() {
    for (const char* dir : {"/usr/bin", "/usr/local/bin"}) {
        const std::string p = std::string(dir) + "/xvfb-run";
        if (access(p.c_str(), X_OK) == 0) return p;
    }
    return "";
}

// Runs the viewer under its own Xvfb. xvfb-run -a picks a free display number from -n on; two
// runs starting together may still pick the same one, so a failed server start is retried.
// The run's result goes to `result` when given.
// `clothsim view` with `args` on an Xvfb server of its own (display numbers apart by `offset`
// for tests that run side by side); fails or skips the test where xvfb-run is missing.
void viewUnderXvfb(const std::vector<std::string>& args, int offset, test::ProcessResult& r) {
    const std::string xvfb = xvfbRun();
    if (xvfb.empty()) {
        if (test::gpuRequiredByEnvironment()) FAIL() << "CLOTH_REQUIRE_GPU=1 but no xvfb-run";
        GTEST_SKIP() << "xvfb-run not installed";
    }
    // The X authority file is the test's own: without -f, xvfb-run makes a directory for it and
    // exits 5 when removing that directory fails, whatever the viewer returned.
    const fs::path auth =
        fs::temp_directory_path() /
        ("clothsim_xauth_" + std::to_string(getpid()) + "_" + std::to_string(offset));
    for (int attempt = 0; attempt < 3; ++attempt) {
        const int display = 100 + int(getpid() % 300) * 3 + attempt + offset;
        std::vector<std::string> argv = {xvfb,      "-a",          "-n", std::to_string(display),
                                         "-f",      auth.string(), "-s", "-screen 0 1280x800x24",
                                         CLOTH_EXE, "view"};
        argv.insert(argv.end(), args.begin(), args.end());
        r = test::runProcess(argv, 120);
        if (r.exitCode == 0 || r.err.find("Xvfb failed to start") == std::string::npos) break;
    }
    std::error_code ignored;
    fs::remove(auth, ignored);
}

void viewScreenshot(const std::string& backend, const fs::path& png,
                    test::ProcessResult* result = nullptr) {
    test::ProcessResult r;
    std::vector<std::string> args = {kScenes + "drape.json", "--backend", backend, "--frames", "12",
                                     "--screenshot",         png.string()};
    if (backend == "gpu") args.insert(args.end(), {"--samples", "4"});  // as asked, any device
    viewUnderXvfb(args, backend == "cpu" ? 0 : backend == "gpu" ? 1000 : 2000, r);
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
    if (result != nullptr) *result = r;
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
}

// A scripted view that ends unstable (explicit Euler at 30 times its bound) writes no state and
// exits 3 naming the step, as run does (DESIGN.md §5). Before, it wrote the state and exited 0.
TEST(ViewerCommand, AnUnstableRunWritesNoStateAndExitsThree) {
    const fs::path d = test::testTempDir();
    const fs::path csv = d / "unstable.csv", png = d / "unstable.png";
    test::ProcessResult r;
    viewUnderXvfb({kScenes + "chain.json", "--backend", "cpu", "--set", "integrator.dt=0.05",
                   "--frames", "5", "--out-csv", csv.string(), "--screenshot", png.string()},
                  3000, r);
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
    CLOTH_SKIP_IF_NO_GL(r);
    EXPECT_EQ(r.exitCode, 3) << test::describe(r);
    EXPECT_NE(r.err.find("unstable at step"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing was written for the unstable state"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(csv));
    EXPECT_FALSE(fs::exists(png)) << "a screenshot of the unstable state";
    fs::remove_all(d);
}

TEST(ViewerCommand, HelpAndBadInputNeedNoDisplay) {
    auto r = test::runProcess({CLOTH_EXE, "view", "--help"}, 30);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("usage: clothsim view"), std::string::npos);
    r = test::runProcess({CLOTH_EXE, "render", "--help"}, 30);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    r = test::runProcess({CLOTH_EXE, "view", kScenes + "missing.json"}, 30);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    r = test::runProcess(
        {CLOTH_EXE, "view", kScenes + "drape.json", "--set", "material.air_damping=-1"}, 30);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find("material.air_damping"), std::string::npos) << r.err;
    r = test::runProcess(
        {CLOTH_EXE, "view", kScenes + "drape.json", "--backend", "gpu", "--precision", "double"},
        30);
    EXPECT_EQ(r.exitCode, 2) << "the GPU in double: " << test::describe(r);
    EXPECT_NE(r.err.find("--precision"), std::string::npos) << r.err;
    r = test::runProcess({CLOTH_EXE, "view", kScenes + "drape.json", "--size", "100000x100000"},
                         30);
    EXPECT_EQ(r.exitCode, 2) << "past 16384 px: " << test::describe(r);
    EXPECT_NE(r.err.find("--size"), std::string::npos) << r.err;
    r = test::runProcess({CLOTH_EXE, "view", kScenes + "drape.json", "--samples", "17"}, 30);
    EXPECT_EQ(r.exitCode, 2) << "past 16 samples: " << test::describe(r);
    EXPECT_NE(r.err.find("--samples"), std::string::npos) << r.err;
    r = test::runProcess({CLOTH_EXE, "view", kScenes + "drape.json", "--screenshot", "s.png",
                          "--out-csv", "./s.png"},
                         30);
    EXPECT_EQ(r.exitCode, 2) << "two outputs in one file: " << test::describe(r);
    EXPECT_NE(r.err.find("give each output a file of its own"), std::string::npos) << r.err;
    r = test::runProcess({CLOTH_EXE, "view", "--out-csv", "/nonexistent-dir/x.csv"}, 30);
    EXPECT_EQ(r.exitCode, 2) << "an unwritable --out-csv: " << test::describe(r);
    EXPECT_NE(r.err.find("--out-csv"), std::string::npos) << r.err;
}

class ViewerWindow : public ::testing::TestWithParam<const char*> {};

TEST_P(ViewerWindow, DrapeScreenshotShowsClothSphereAndGround) {
    const fs::path d = test::testTempDir();
    const fs::path png = d / "view.png";
    test::ProcessResult r;
    viewScreenshot(GetParam(), png, &r);
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
    // --backend auto says what it picked for the window's device, and why: the CPU on a software
    // rasteriser (Xvfb's is Mesa's llvmpipe).
    if (GetParam() == std::string("auto")) {
        EXPECT_NE(r.err.find("clothsim: backend auto: "), std::string::npos) << r.err;
        if (r.err.find("software rasteriser") != std::string::npos) {
            EXPECT_NE(r.err.find("backend auto: cpu, as the OpenGL device, "), std::string::npos)
                << r.err;
            // Multisampling halves a software rasteriser's frame rate: the window goes without.
            EXPECT_NE(r.err.find("without multisampling (GL_SAMPLES 0)"), std::string::npos)
                << r.err;
        }
    }
    if (GetParam() == std::string("gpu")) {  // --samples 4 given: kept on any device
        EXPECT_EQ(r.err.find("without multisampling"), std::string::npos) << r.err;
    }
    const test::Picture p = test::loadPng(png.string());
    ASSERT_EQ(p.width, 1280);
    ASSERT_EQ(p.height, 800);
    const test::ColourCounts view = test::countColours(p, 400);  // right of the panel
    EXPECT_GT(view.back, view.total / 20) << "the cloth, seen from above";
    EXPECT_GT(view.sphere, view.total / 50) << "the sphere under it";
    EXPECT_GT(view.grey, view.total / 10) << "the ground";
    const test::ColourCounts panel = test::countColours(test::Picture{
        400, p.height, [&] {
            std::vector<std::uint8_t> left;
            for (int y = 0; y < p.height; ++y)
                left.insert(left.end(), p.rgb.begin() + std::ptrdiff_t(y) * p.width * 3,
                            p.rgb.begin() + (std::ptrdiff_t(y) * p.width + 400) * 3);
            return left;
        }()});
    EXPECT_GT(panel.distinct, 10) << "the control panel is drawn";
    fs::remove_all(d);
}

INSTANTIATE_TEST_SUITE_P(Backends, ViewerWindow, ::testing::Values("cpu", "gpu", "auto"));

}  // namespace
}  // namespace cloth
