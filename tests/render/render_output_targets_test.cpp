// `render` writes its PNGs through the same output helper as `run` (README, "Reading the
// output"): a symlinked --png writes its target and stays a link; a --frames DIR that cannot be a
// directory is exit 2 before any step runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "render/image_checks.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kDrape = CLOTH_SOURCE_DIR "/scenes/drape.json";

TEST(RenderOutputTargets, SymlinkedPngWritesItsTargetAndStaysALink) {
    const fs::path d = test::freshTempDir("render_output_targets_test", "symlink");
    { std::ofstream(d / "target.png") << "previous\n"; }
    fs::create_symlink("target.png", d / "link.png");
    const auto r = runProcess({kExe, "render", kDrape, "--steps", "0", "--size", "32x24", "--png",
                               (d / "link.png").string(), "--set", "cloth.resolution=[4, 4]"},
                              120);
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    ASSERT_TRUE(fs::is_symlink(d / "link.png"));
    const test::Picture p = test::loadPng((d / "target.png").string());
    EXPECT_EQ(p.width, 32);
    EXPECT_EQ(p.height, 24);
    EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 2);
    fs::remove_all(d);
}

TEST(RenderOutputTargets, FramesUnderARegularFileIsExitTwoBeforeAnyStep) {
    const fs::path d = test::freshTempDir("render_output_targets_test", "frames_file");
    { std::ofstream(d / "file") << "not a folder\n"; }
    const std::string frames = (d / "file" / "frames").string();
    const auto r = runProcess({kExe, "render", kDrape, "--steps", "20", "--every", "10", "--frames",
                               frames, "--size", "32x24"},
                              120);
    CLOTH_SKIP_IF_NO_GL(r);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find("--frames"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(frames), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    fs::remove_all(d);
}

}  // namespace
}  // namespace cloth
