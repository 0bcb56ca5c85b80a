// The viewer under real input: tests/viewer/drive_viewer.sh opens `clothsim view` on an Xvfb
// server of its own and drives the window with xdotool's XTEST events (what a mouse and a
// keyboard send), then the viewer's last frame and state are checked here. Every session pauses
// (Space) and resets (R) first, so what follows is deterministic: N steps one frame's substeps,
// Ctrl+click pins, a left drag on the cloth grabs it, a left drag on empty space orbits, Ctrl+Q
// closes the window. The keys are quick taps, released before the next frame: they reach the
// viewer only through its key latch (ViewerUi::keysPressed).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "render/image_checks.h"
#include "scene/scene_loader.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;

const std::string kExe = CLOTH_EXE;
const std::string kScene = CLOTH_SOURCE_DIR "/scenes/hanging.json";
const std::string kDriver = CLOTH_SOURCE_DIR "/tests/viewer/drive_viewer.sh";

bool onPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':'))
        if (!dir.empty() && ::access((dir + "/" + program).c_str(), X_OK) == 0) return true;
    return false;
}

struct Vertex {
    glm::dvec3 x, v;
};
using State = std::map<std::pair<int, int>, Vertex>;

State readCsv(const fs::path& file) {
    State s;
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);  // i,j,x,y,z,vx,vy,vz
    while (std::getline(in, line)) {
        int i = 0, j = 0;
        Vertex q;
        if (std::sscanf(line.c_str(), "%d,%d,%lf,%lf,%lf,%lf,%lf,%lf", &i, &j, &q.x.x, &q.x.y,
                        &q.x.z, &q.v.x, &q.v.y, &q.v.z) == 8)
            s[{i, j}] = q;
    }
    return s;
}

std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class ViewerInput : public ::testing::Test {
protected:
    void SetUp() override {
        for (const char* program : {"Xvfb", "xdotool"}) {
            if (onPath(program)) continue;
            const char* required = std::getenv("CLOTH_REQUIRE_GPU");
            if (required && std::string(required) == "1")
                GTEST_FAIL() << "CLOTH_REQUIRE_GPU=1 but " << program << " is not installed";
            GTEST_SKIP() << program << " is not installed";
        }
        dir_ = test::freshTempDir("viewer_input",
                                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    }
    void TearDown() override {
        if (!HasFailure() && !dir_.empty()) fs::remove_all(dir_);
    }

    // The session's state and last frame, after checking it ran.
    State drive(const std::string& session) {
        const test::ProcessResult r =
            test::runProcess({"/bin/sh", kDriver, kExe, kScene, dir_.string(), session}, 180);
        EXPECT_EQ(r.exitCode, 0) << test::describe(r) << readFile(dir_ / (session + ".log"));
        const test::Picture p = test::loadPng((dir_ / (session + ".png")).string());
        EXPECT_EQ(p.width, 1280) << session << ": no screenshot of the last frame";
        if (p.width == 1280) {
            const test::ColourCounts view = test::countColours(p, 400);
            EXPECT_GT(view.front + view.back, view.total / 20) << session << ": the cloth is drawn";
        }
        return readCsv(dir_ / (session + ".csv"));
    }

    // `run` of the same scene for `steps` steps (CPU double, as the sessions), the reference.
    State run(long steps) {
        const fs::path csv = dir_ / ("run_" + std::to_string(steps) + ".csv");
        const test::ProcessResult r = test::runProcess(
            {kExe, "run", kScene, "--steps", std::to_string(steps), "--out-csv", csv.string()}, 60);
        EXPECT_EQ(r.exitCode, 0) << test::describe(r);
        return readCsv(csv);
    }

    long substeps() { return loadScene(kScene).integrator.substeps; }

    fs::path dir_;
};

// Space pauses, R goes back to the rest state and stays paused, each N steps one frame's
// substeps: after three N the viewer's state is `run --steps 3·substeps`, to the bit.
TEST_F(ViewerInput, PauseResetAndStepGiveTheRunsStateBitForBit) {
    drive("step");
    if (HasFailure()) return;
    const fs::path ref = dir_ / ("run_" + std::to_string(3 * substeps()) + ".csv");
    run(3 * substeps());
    EXPECT_EQ(readFile(dir_ / "step.csv"), readFile(ref));
}

// Ctrl+click on the cloth pins the vertex under the cursor where it is (the rest state): over
// the next four frames it keeps its rest position and no velocity, as the scene's own pins do.
TEST_F(ViewerInput, CtrlClickPinsTheVertexUnderTheCursor) {
    const State s = drive("pin");
    if (HasFailure()) return;
    const Scene scene = loadScene(kScene);
    const Grid grid = scene.grid();
    std::vector<std::pair<int, int>> still;
    for (const auto& [ij, q] : s)
        if (q.v == glm::dvec3(0)) still.push_back(ij);
    ASSERT_EQ(still.size(), scene.pins.size() + 1) << "one vertex more than the scene pins";
    for (const auto& ij : still) {
        bool scenePin = false;
        for (const Pin& p : scene.pins) scenePin |= (p.i == ij.first && p.j == ij.second);
        if (scenePin) continue;
        std::printf("pinned by Ctrl+click: (%d, %d)\n", ij.first, ij.second);
        EXPECT_GT(ij.first, 0);
        EXPECT_LT(ij.first, grid.nu - 1);
        EXPECT_GT(ij.second, 0);
        EXPECT_LT(ij.second, grid.nv - 1);
        const glm::dvec3 rest = grid.restPosition(ij.first, ij.second);
        EXPECT_LT(glm::length(s.at(ij).x - rest), 1e-6) << "pinned where it rested";
    }
}

// A left drag from the cloth grabs a vertex and pulls it towards the cursor, 60 px to the
// right: on this view the horizontal, so the cloth moves sideways against the run that nobody
// touched, far more than it moves up or down.
TEST_F(ViewerInput, LeftDragOnTheClothGrabsAndPullsIt) {
    const State s = drive("grab");
    if (HasFailure()) return;
    const State ref = run(4 * substeps());
    glm::dvec3 largest(0);
    for (const auto& [ij, q] : s) {
        const glm::dvec3 d = q.x - ref.at(ij).x;
        if (glm::length(d) > glm::length(largest)) largest = d;
    }
    std::printf("largest displacement by the grab: (%.4f, %.4f, %.4f) m\n", largest.x, largest.y,
                largest.z);
    EXPECT_GT(glm::length(largest), 0.05);
    EXPECT_LT(std::abs(largest.y), std::hypot(largest.x, largest.z)) << "pulled sideways";
}

// A left drag on empty space orbits the camera: the cloth, still paused at rest, is seen from
// elsewhere, so the view right of the panel changes (15% of its pixels seen; P's screenshot before
// the drag against the last frame after it).
TEST_F(ViewerInput, LeftDragOnEmptySpaceOrbitsTheView) {
    const State s = drive("orbit");
    if (HasFailure()) return;
    const test::Picture before = test::loadPng((dir_ / "out" / "screenshot.png").string());
    const test::Picture after = test::loadPng((dir_ / "orbit.png").string());
    ASSERT_EQ(before.width, after.width) << "P wrote no screenshot";
    ASSERT_EQ(before.height, after.height);
    long changed = 0, total = 0;
    for (int y = 0; y < after.height; ++y)
        for (int x = 400; x < after.width; ++x, ++total) {
            const std::size_t k = (std::size_t(y) * after.width + x) * 3;
            int d = 0;
            for (int c = 0; c < 3; ++c)
                d += std::abs(int(before.rgb[k + c]) - int(after.rgb[k + c]));
            changed += d > 30;
        }
    std::printf("orbit: %.1f%% of the view changed\n", 100.0 * double(changed) / double(total));
    EXPECT_GT(changed, total / 10);
    // The cloth did not move: paused at rest.
    const Grid grid = loadScene(kScene).grid();
    for (const auto& [ij, q] : s)
        EXPECT_LT(glm::length(q.x - grid.restPosition(ij.first, ij.second)), 1e-9);
}

}  // namespace
}  // namespace cloth
