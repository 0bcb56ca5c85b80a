// --backend auto (DESIGN.md §5): the GPU backend when the OpenGL device is hardware, else the CPU,
// since a software rasteriser (llvmpipe) runs the GPU backend about 10-30x slower than the CPU
// backend. `info` says which device is software and what auto picks and why; `run` accepts auto
// (its default stays cpu), `render` and `view` default to it and say what they picked; --backend
// gpu on a software device runs with a one-line notice. What is expected follows the device `info`
// reports, so the laws hold on a machine with a hardware GPU, with llvmpipe only, or with none.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "support/gl_required.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kSpring = CLOTH_SOURCE_DIR "/scenes/spring.json";
const std::string kChain = CLOTH_SOURCE_DIR "/scenes/chain.json";

enum class Device { None, Software, Hardware };

// The OpenGL device as `clothsim info` reports it.
Device infoDevice(const std::string& info) {
    if (info.find("gpu          unavailable") != std::string::npos) return Device::None;
    return info.find("[software]") != std::string::npos ? Device::Software : Device::Hardware;
}

Device thisDevice() {
    static const Device device = infoDevice(runProcess({kExe, "info"}, 60).out);
    return device;
}

// The backend auto picks on this device, as its summary and messages name it.
std::string autoPick() {
    return thisDevice() == Device::Hardware ? "gpu" : "cpu";
}

long lines(const std::string& text) {
    return std::count(text.begin(), text.end(), '\n');
}

TEST(BackendAuto, InfoSaysWhichDeviceIsSoftwareAndWhatAutoPicks) {
    const auto r = runProcess({kExe, "info"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const size_t at = r.out.find("\nauto         ");
    ASSERT_NE(at, std::string::npos) << r.out;
    const std::string line = r.out.substr(at + 1, r.out.find('\n', at + 1) - at - 1);
    switch (infoDevice(r.out)) {
        case Device::Software:
            EXPECT_NE(r.out.find("EGL devices:"), std::string::npos) << r.out;
            EXPECT_EQ(line.rfind("auto         cpu, as the OpenGL device, ", 0), 0u) << line;
            EXPECT_NE(line.find("is a software rasteriser, where the GPU backend runs about "
                                "10-30x slower than the CPU backend"),
                      std::string::npos)
                << line;
            break;
        case Device::Hardware:
            EXPECT_EQ(line.rfind("auto         gpu, as the OpenGL device, ", 0), 0u) << line;
            EXPECT_NE(line.find("is a hardware GPU"), std::string::npos) << line;
            break;
        case Device::None:
            EXPECT_EQ(line.rfind("auto         cpu, as ", 0), 0u) << line;
            break;
    }
}

// Law: run's default stays the CPU, silently; --backend auto says its pick and reason on stderr
// in one line and runs there; --quiet keeps it quiet.
TEST(BackendAuto, RunAcceptsAutoAndSaysWhatItPicked) {
    const auto plain = runProcess({kExe, "run", kSpring, "--steps", "10"}, 60);
    ASSERT_EQ(plain.exitCode, 0) << test::describe(plain);
    EXPECT_EQ(plain.err, "");
    EXPECT_NE(plain.out.find("(cpu double"), std::string::npos) << plain.out;

    const auto r = runProcess({kExe, "run", kSpring, "--steps", "10", "--backend", "auto"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_EQ(r.err.rfind("clothsim: backend auto: " + autoPick() + ", as ", 0), 0u) << r.err;
    EXPECT_EQ(lines(r.err), 1) << r.err;
    EXPECT_NE(r.out.find(std::string("(") + autoPick() + " "), std::string::npos) << r.out;
    if (thisDevice() == Device::Software) {
        EXPECT_NE(r.err.find("software rasteriser"), std::string::npos) << r.err;
    }

    const auto quiet =
        runProcess({kExe, "run", kSpring, "--steps", "10", "--backend", "auto", "--quiet"}, 60);
    EXPECT_EQ(quiet.exitCode, 0) << test::describe(quiet);
    EXPECT_EQ(quiet.out + quiet.err, "");
}

// Law: where EGL offers no OpenGL at all (here: libglvnd pointed at no vendor), auto runs on the
// CPU and its one line says why, the reason whole: each platform tried and what it said (in a
// build without the GPU backend, that it has none).
TEST(BackendAuto, WithoutAnyOpenGlAutoRunsOnTheCpuAndSaysWhy) {
    const auto r = runProcess({"/usr/bin/env", "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent.json",
                               kExe, "run", kSpring, "--steps", "10", "--backend", "auto"},
                              60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("(cpu "), std::string::npos) << r.out;
    ASSERT_EQ(lines(r.err), 1) << r.err;
    ASSERT_EQ(r.err.rfind("clothsim: backend auto: cpu, as ", 0), 0u) << r.err;
    EXPECT_NE(r.err.substr(r.err.size() - 2), ":\n") << r.err;  // no reason cut off at a colon
    if (r.err.find("built without the GPU backend") != std::string::npos) return;
    const std::string why =
        "clothsim: backend auto: cpu, as the GPU backend has no OpenGL 4.3 "
        "context: no headless OpenGL 4.3+ context could be made: EGL ";
    EXPECT_EQ(r.err.rfind(why, 0), 0u) << r.err;
    EXPECT_GT(r.err.size(), why.size() + 10) << r.err;  // a platform and its error follow
}

// Law: the GPU computes in float, so auto with --precision double picks the CPU, and says so.
TEST(BackendAuto, PrecisionDoublePicksTheCpu) {
    const auto r = runProcess(
        {kExe, "run", kSpring, "--steps", "10", "--backend", "auto", "--precision", "double"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.err.find("backend auto: cpu, as --precision double asks"), std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("(cpu double"), std::string::npos) << r.out;
}

// Law: --backend gpu on a software rasteriser runs, with one line on stderr that says so; on a
// hardware GPU it says nothing.
TEST(BackendAuto, GpuOnASoftwareDeviceRunsWithANotice) {
    const auto r = runProcess({kExe, "run", kSpring, "--steps", "10", "--backend", "gpu"}, 60);
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("(gpu"), std::string::npos) << r.out;
    if (thisDevice() == Device::Software) {
        EXPECT_EQ(r.err.rfind("clothsim: note: the GPU backend runs on ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(", a software rasteriser, about 10-30x slower than the CPU backend "
                             "there (--backend cpu or auto picks the CPU)"),
                  std::string::npos)
            << r.err;
        EXPECT_EQ(lines(r.err), 1) << r.err;
    } else {
        EXPECT_EQ(r.err.find("note:"), std::string::npos) << r.err;
    }
}

// Law: render's default is auto; it says what it picked and why, and draws with it.
TEST(BackendAuto, RenderDefaultsToAutoAndSaysWhy) {
    const fs::path png = test::freshTempDir("backend_auto_test", "render") / "chain.png";
    const auto r = runProcess(
        {kExe, "render", kChain, "--steps", "10", "--size", "64x64", "--png", png.string()}, 120);
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.err.find("clothsim: backend auto: " + autoPick() + ", as the OpenGL device, "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find(", " + autoPick() + " "), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(png));
}

// Law: a backend other than cpu, gpu or auto is invalid input naming the flag and the choices,
// on every command that takes one (view where this build has the viewer).
TEST(BackendAuto, OtherValuesAreRefusedNamingTheChoices) {
    for (const char* command : {"run", "render", "view"}) {
        const auto r = runProcess({kExe, command, kSpring, "--backend", "automatic"}, 60);
        if (r.exitCode == 4 && r.err.find("built without the viewer") != std::string::npos)
            continue;  // such a build reads no view options
        EXPECT_EQ(r.exitCode, 2) << command << ": " << test::describe(r);
        EXPECT_NE(r.err.find("--backend: expected cpu, gpu or auto, got 'automatic'"),
                  std::string::npos)
            << command << ": " << r.err;
    }
}

}  // namespace
}  // namespace cloth
