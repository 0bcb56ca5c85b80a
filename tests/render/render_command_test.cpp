// `clothsim render` headless (EGL): the picture shows the cloth, its two sides, the sphere and
// the ground where they project; errors map to exit codes 2 and 3 and write no file.
#include <gtest/gtest.h>

#include <filesystem>

#include "render/image_checks.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kScenes = CLOTH_SOURCE_DIR "/scenes/";

fs::path tempDir(const std::string& name) {
    return test::freshTempDir("render_test", name);
}

test::ProcessResult render(const std::vector<std::string>& extra) {
    std::vector<std::string> argv = {kExe, "render"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    return runProcess(argv, 120);
}

TEST(RenderCommand, DrapeAtRestShowsClothSphereAndGround) {
    const fs::path png = tempDir("rest") / "drape.png";
    const auto r = render(
        {kScenes + "drape.json", "--steps", "0", "--size", "480x360", "--png", png.string()});
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const test::Picture p = test::loadPng(png.string());
    ASSERT_EQ(p.width, 480);
    ASSERT_EQ(p.height, 360);
    const test::ColourCounts c = test::countColours(p);
    // Seen from above, the flat cloth shows its back (its normal û × v̂ points down).
    EXPECT_GT(c.back, c.total / 20) << "cloth";
    EXPECT_GT(c.sphere, c.total / 50) << "sphere below the cloth";
    EXPECT_GT(c.grey, c.total / 10) << "ground plane";
    EXPECT_GT(c.distinct, 20) << "not a blank picture";
}

TEST(RenderCommand, FinishedDrapeShowsBothSidesOfTheCloth) {
    const fs::path png = tempDir("final") / "drape.png";
    const auto r = render({kScenes + "drape.json", "--size", "480x360", "--png", png.string()});
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const test::ColourCounts c = test::countColours(test::loadPng(png.string()));
    EXPECT_GT(c.back, c.total / 50);
    EXPECT_GT(c.front, 20) << "the hanging edges turn the front (orange) side to the camera";
    EXPECT_GT(c.grey, c.total / 10);
}

// The GPU picture is drawn from the GPU solver's own buffers; it shows the same cloth: the drape
// after 0.28 s (700 steps), just landed on the sphere's top. Measured: no channel differs by
// more than 24 at 700 steps, 4 at 800; from 900 on (611) the folds forming over the sphere,
// whose places float rounding picks, part the two pictures.
TEST(RenderCommand, GpuAndCpuPicturesAgree) {
    const fs::path d = tempDir("parity");
    for (const char* backend : {"cpu", "gpu"}) {
        const auto r =
            render({kScenes + "drape.json", "--backend", backend, "--steps", "700", "--size",
                    "320x240", "--png", (d / (std::string(backend) + ".png")).string()});
        CLOTH_SKIP_IF_NO_GL(r);
        ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    }
    const test::Picture cpu = test::loadPng((d / "cpu.png").string());
    const test::Picture gpu = test::loadPng((d / "gpu.png").string());
    ASSERT_EQ(cpu.rgb.size(), gpu.rgb.size());
    long differ = 0;
    for (std::size_t k = 0; k < cpu.rgb.size(); ++k)
        differ += std::abs(cpu.rgb[k] - gpu.rgb[k]) > 24;
    EXPECT_LT(differ, long(cpu.rgb.size() / 200)) << "more than 0.5 % of the channels differ";
    EXPECT_GT(test::countColours(gpu).back, long(cpu.rgb.size() / 3 / 20));
    fs::remove_all(d);
}

// Pixels of the strain map's red (a stretched spring), pins' markers included.
long redPixels(const test::Picture& p) {
    long red = 0;
    for (std::size_t k = 0; k + 2 < p.rgb.size(); k += 3)
        red += p.rgb[k] > 80 && p.rgb[k] > 2 * p.rgb[k + 1] && p.rgb[k] > 2 * p.rgb[k + 2];
    return red;
}

// The denim hanging from two corners after 0.3 s, full colour at 1 % strain: its springs next to
// the pins stretch by up to 3.8 %, half the springs by under 0.13 %. The picture at rest (no
// strain; its red is the two pins' markers) is the baseline.
TEST(RenderCommand, StrainModeColoursAStretchedCloth) {
    const fs::path dir = tempDir("strain");
    long red[2] = {};
    for (int k = 0; k < 2; ++k) {
        const fs::path png = dir / (k == 0 ? "rest.png" : "hanging.png");
        const auto r = render({kScenes + "hanging.json", "--steps", k == 0 ? "0" : "1000",
                               "--colour", "strain", "--strain-scale", "0.01", "--size", "320x240",
                               "--png", png.string()});
        CLOTH_SKIP_IF_NO_GL(r);
        ASSERT_EQ(r.exitCode, 0) << test::describe(r);
        red[k] = redPixels(test::loadPng(png.string()));
    }
    EXPECT_GT(red[1], red[0] + 50)
        << "a cloth hanging from two corners is stretched near the pins; at rest " << red[0];
}

TEST(RenderCommand, ChainIsDrawn) {
    const fs::path png = tempDir("chain") / "chain.png";
    const auto r = render(
        {kScenes + "chain.json", "--steps", "100", "--size", "320x240", "--png", png.string()});
    CLOTH_SKIP_IF_NO_GL(r);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_GT(test::countColours(test::loadPng(png.string())).front, 30);
}

TEST(RenderCommand, BadInputIsExitTwoAndUnstableIsExitThreeWithoutAFile) {
    const fs::path d = tempDir("errors");
    auto r = render({kScenes + "nope.json", "--png", (d / "a.png").string()});
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    r = render({kScenes + "drape.json", "--size", "12x", "--png", (d / "a.png").string()});
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    r = render({kScenes + "drape.json", "--png", (d / "missing" / "a.png").string()});
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    r = render({kScenes + "hanging.json", "--set", "integrator.dt=0.01", "--steps", "2000", "--png",
                (d / "b.png").string()});
    CLOTH_SKIP_IF_NO_GL(r);
    EXPECT_EQ(r.exitCode, 3) << test::describe(r);
    EXPECT_FALSE(fs::exists(d / "b.png"));
    fs::remove_all(d);
}

}  // namespace
}  // namespace cloth
