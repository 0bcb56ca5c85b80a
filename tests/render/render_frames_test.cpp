// `clothsim render --frames DIR --every K`: a PNG every K steps and the initial
// one, names sorting in step order, each a picture of the requested size; an MP4 when ffmpeg is
// on PATH, and when it is not a clear message and exit 0 with the PNGs written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "render/image_checks.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kDrape = CLOTH_SOURCE_DIR "/scenes/drape.json";

bool ffmpegOnPath() {
    return std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
}

TEST(RenderFrames, PngSequenceSortsInStepOrderAndSaysWhetherAnMp4WasMade) {
    const fs::path dir = test::freshTempDir("render_frames_test", "seq") / "frames";
    const auto r = runProcess(
        {kExe, "render", kDrape, "--steps", "60", "--every", "20", "--frames", dir.string(),
         "--size", "64x48", "--set", "cloth.resolution=[6, 6]", "--set", "integrator.dt=1e-3"},
        120);
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::vector<std::string> pngs;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".png") pngs.push_back(e.path().filename());
    std::sort(pngs.begin(), pngs.end());
    ASSERT_EQ(pngs.size(), 4u);  // steps 0, 20, 40, 60
    for (size_t k = 0; k < pngs.size(); ++k) {
        char want[64];
        std::snprintf(want, sizeof want, "drape_%06zu.png", 20 * k);
        EXPECT_EQ(pngs[k], want);
        const test::Picture p = test::loadPng((dir / pngs[k]).string());
        EXPECT_EQ(p.width, 64);
        EXPECT_EQ(p.height, 48);
    }
    if (ffmpegOnPath()) {
        ASSERT_TRUE(fs::exists(dir / "drape.mp4")) << r.out;
        // A real encoder (Debian's ffmpeg package ships ffprobe): one video frame per PNG, at their
        // size.
        const auto probe = runProcess(
            {"/bin/sh", "-c",
             "ffprobe -v error -count_frames -show_entries stream=width,height,nb_read_frames "
             "-of default=nw=1 '" +
                 (dir / "drape.mp4").string() + "'"},
            60);
        ASSERT_EQ(probe.exitCode, 0) << test::describe(probe);
        EXPECT_NE(probe.out.find("width=64"), std::string::npos) << probe.out;
        EXPECT_NE(probe.out.find("height=48"), std::string::npos) << probe.out;
        EXPECT_NE(probe.out.find("nb_read_frames=4"), std::string::npos) << probe.out;
    } else {
        EXPECT_NE(r.out.find("ffmpeg is not on PATH: no MP4 was made"), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(dir / "drape.mp4"));
    }
}

// With an ffmpeg on PATH (here a stand-in script that records its arguments and creates its
// output), the MP4 is asked for from the step-ordered PNGs at --fps and reported as written.
TEST(RenderFrames, CallsFfmpegOnThePngSequenceWhenItIsOnPath) {
    const fs::path base = test::freshTempDir("render_frames_test", "ffmpeg");
    const fs::path bin = base / "bin", dir = base / "frames";
    fs::create_directories(bin);
    {
        std::ofstream script(bin / "ffmpeg");
        script << "#!/bin/sh\necho \"$@\" > \"" << (base / "args.txt").string()
               << "\"\nfor last; do :; done\ntouch \"$last\"\n";
    }
    fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
    const std::string oldPath = std::getenv("PATH") ? std::getenv("PATH") : "";
    setenv("PATH", (bin.string() + ":" + oldPath).c_str(), 1);
    const auto r = runProcess(
        {kExe, "render", kDrape, "--steps", "2", "--every", "1", "--frames", dir.string(), "--size",
         "32x32", "--fps", "12", "--set", "cloth.resolution=[4, 4]"},
        120);
    setenv("PATH", oldPath.c_str(), 1);
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(fs::exists(dir / "drape.mp4"));
    EXPECT_NE(r.out.find("wrote " + (dir / "drape.mp4").string()), std::string::npos) << r.out;
    std::ifstream in(base / "args.txt");
    const std::string args((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(args.find("-framerate 12"), std::string::npos) << args;
    EXPECT_NE(args.find("-pattern_type glob -i " + (dir / "drape_*.png").string()),
              std::string::npos)
        << args;
}

// Law: --frames and --every come together, and render needs --png or --frames (exit 2).
TEST(RenderFrames, FramesWithoutEveryOrNoOutputIsAnInputError) {
    const fs::path dir = test::freshTempDir("render_frames_test", "bad");
    EXPECT_EQ(runProcess({kExe, "render", kDrape, "--frames", dir.string()}, 30).exitCode, 2);
    EXPECT_EQ(runProcess({kExe, "render", kDrape, "--every", "3", "--png", "x.png"}, 30).exitCode,
              2);
    EXPECT_EQ(runProcess({kExe, "render", kDrape}, 30).exitCode, 2);
    EXPECT_EQ(runProcess({kExe, "render", kDrape, "--png", "x.png", "--fps", "0"}, 30).exitCode, 2);
}

}  // namespace
}  // namespace cloth
