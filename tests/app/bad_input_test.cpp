// Malformed input never crashes clothsim: every bad scene, --set override and argument ends in
// exit code 2 with a message naming the file, the key path and the reason (DESIGN.md §4, §5).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "model/errors.h"
#include "scene/scene_loader.h"
#include "support/bad_scenes.h"
#include "support/process.h"
#include "support/sanitized.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::BadScene;
using test::kBadDir;
using test::kGoodScene;
using test::loadManifest;
using test::ProcessResult;
using test::readFile;
using test::runProcess;

constexpr double kTimeout = 30;  // [s] a bad scene is refused at once; this only catches hangs
const std::string kExe = CLOTH_EXE;

// Parse errors must point into the file: nlohmann says "line 3, column 5".
bool isSyntaxError(const std::string& file) {
    static const std::vector<std::string> kFiles = {
        "syntax_error.json",  "truncated.json",   "trailing_garbage.json", "comment.json",
        "single_quotes.json", "nan_literal.json", "bom_then_garbage.json"};
    return std::find(kFiles.begin(), kFiles.end(), file) != kFiles.end();
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

// Letters left once the file's path and the key are taken out: a reason, not only a location.
bool hasReason(std::string err, const std::string& path, const std::vector<std::string>& keys) {
    for (const std::string& cut : {path, fs::path(path).filename().string()}) {
        for (size_t at; !cut.empty() && (at = err.find(cut)) != std::string::npos;)
            err.erase(at, cut.size());
    }
    for (const std::string& k : keys) {
        for (size_t at; !k.empty() && (at = err.find(k)) != std::string::npos;)
            err.erase(at, k.size());
    }
    const auto letters =
        std::count_if(err.begin(), err.end(), [](unsigned char c) { return std::isalpha(c); });
    return letters >= 6;
}

// The checks every refused input shares: exit 2 (not a crash, not a hang, not "internal"),
// stderr names the file (when there is one), one of the keys (when one applies) and a reason.
void expectInvalidInput(const ProcessResult& r, const std::string& path,
                        const std::vector<std::string>& keys) {
    ASSERT_FALSE(r.crashed) << test::describe(r);
    ASSERT_FALSE(r.timedOut) << test::describe(r);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    if (!path.empty()) {
        EXPECT_TRUE(contains(r.err, fs::path(path).filename().string()))
            << "stderr does not name the file " << path << "\n"
            << test::describe(r);
    }
    if (!keys.empty() && !keys.front().empty()) {
        const bool named = std::any_of(keys.begin(), keys.end(),
                                       [&](const std::string& k) { return contains(r.err, k); });
        EXPECT_TRUE(named) << "stderr does not name the key path " << keys.front() << "\n"
                           << test::describe(r);
    }
    EXPECT_TRUE(hasReason(r.err, path, keys)) << "stderr gives no reason\n" << test::describe(r);
    // A clear message is a line or two, not an echo of the offending document.
    EXPECT_LT(r.err.size(), 16384u) << "stderr is " << r.err.size() << " bytes";
}

// ---- every file in tests/data/bad_scenes, through validate and run ------------------------

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, ValidateExitsTwoNamingFileAndKey) {
    const BadScene& b = GetParam();
    const std::string path = (kBadDir / b.file).string();
    const ProcessResult r = runProcess({kExe, "validate", path}, kTimeout);
    expectInvalidInput(r, path, b.keys);
    if (isSyntaxError(b.file)) {
        EXPECT_TRUE(std::regex_search(r.err, std::regex(R"(line\D{0,3}\d+)", std::regex::icase)))
            << "a syntax error should give the line\n"
            << test::describe(r);
        EXPECT_TRUE(
            std::regex_search(r.err, std::regex(R"(col(umn)?\D{0,3}\d+)", std::regex::icase)))
            << "a syntax error should give the column\n"
            << test::describe(r);
    }
}

TEST_P(BadSceneTest, RunExitsTwoNamingFileAndKey) {
    const BadScene& b = GetParam();
    const std::string path = (kBadDir / b.file).string();
    expectInvalidInput(runProcess({kExe, "run", path, "--steps", "1", "--quiet"}, kTimeout), path,
                       b.keys);
}

std::string testName(const ::testing::TestParamInfo<BadScene>& info) {
    std::string n = info.param.file.substr(0, info.param.file.rfind('.'));
    for (char& c : n) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    }
    return n;
}

INSTANTIATE_TEST_SUITE_P(BadScenes, BadSceneTest, ::testing::ValuesIn(loadManifest()), testName);

TEST(BadSceneManifest, ListsEveryFileAndEnoughOfThem) {
    const std::vector<BadScene> manifest = loadManifest();
    EXPECT_GE(manifest.size(), 35u);
    for (const auto& entry : fs::directory_iterator(kBadDir)) {
        const std::string name = entry.path().filename().string();
        if (name == "expected.json") continue;
        EXPECT_TRUE(std::any_of(manifest.begin(), manifest.end(),
                                [&](const BadScene& b) { return b.file == name; }))
            << name << " is missing from expected.json";
    }
    for (const BadScene& b : manifest) EXPECT_TRUE(fs::exists(kBadDir / b.file)) << b.file;
}

// The bad scenes are mutations of good_scene.json, which must itself pass: otherwise every
// "bad" file might be refused for the wrong reason.
TEST(GoodScene, ValidatesAndRuns) {
    const ProcessResult v = runProcess({kExe, "validate", kGoodScene.string()}, kTimeout);
    EXPECT_EQ(v.exitCode, 0) << test::describe(v);
    const ProcessResult r =
        runProcess({kExe, "run", kGoodScene.string(), "--steps", "1", "--quiet"}, kTimeout);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
}

// ---- --set overrides ---------------------------------------------------------------------

struct BadOverride {
    std::string set;  // the argument after --set
    std::string key;  // the key path stderr must name
};

void PrintTo(const BadOverride& o, std::ostream* os) {
    *os << "--set " << o.set;
}

class BadOverrideTest : public ::testing::TestWithParam<BadOverride> {};

TEST_P(BadOverrideTest, RunExitsTwoNamingKey) {
    const BadOverride& o = GetParam();
    const ProcessResult r = runProcess(
        {kExe, "run", kGoodScene.string(), "--steps", "1", "--quiet", "--set", o.set}, kTimeout);
    expectInvalidInput(r, "", {o.key});
}

INSTANTIATE_TEST_SUITE_P(
    Overrides, BadOverrideTest,
    ::testing::Values(BadOverride{"integrator.dt=-1", "integrator.dt"},
                      BadOverride{"integrator.dt=0", "integrator.dt"},
                      BadOverride{"integrator.dt=notjson", "integrator.dt"},
                      BadOverride{"integrator.dt=\"NaN\"", "integrator.dt"},
                      BadOverride{"integrator.dt=1e999", "integrator.dt"},
                      BadOverride{"springs.bnd=3", "springs.bnd"},
                      BadOverride{"colour=1", "colour"},
                      BadOverride{"cloth.resolution=[100000,100000]", "cloth.resolution"},
                      BadOverride{"cloth.resolution=[1,1]", "cloth.resolution"},
                      BadOverride{"cloth=5", "cloth"}, BadOverride{"pins=[[9,9]]", "pins[0]"},
                      BadOverride{"pins[0]=[0,99]", "pins[0]"},
                      BadOverride{"colliders[99999999999999999999].radius=1", "colliders"},
                      BadOverride{"colliders[1].radius=-1", "colliders[1].radius"},
                      BadOverride{"nokey", "nokey"}, BadOverride{"=5", ""}),
    [](const ::testing::TestParamInfo<BadOverride>& p) {
        return "case" + std::to_string(p.index);
    });

// A key set twice: the later wins, and stderr says so in one line naming the key.
TEST(RepeatedOverride, LaterWinsWithOneNoticeNamingTheKey) {
    for (const std::string cmd : {"validate", "run"}) {
        SCOPED_TRACE(cmd);
        std::vector<std::string> argv = {
            kExe, cmd, kGoodScene.string(), "--set", "springs.bend=100", "--set", "springs.bend=0"};
        if (cmd == "run") argv.insert(argv.end(), {"--steps", "1"});
        const ProcessResult r = runProcess(argv, kTimeout);
        EXPECT_EQ(r.exitCode, 0) << test::describe(r);
        EXPECT_TRUE(contains(r.err, "springs.bend")) << test::describe(r);
        std::size_t notes = 0;  // other lines may warn about the scene itself (its Δt)
        for (std::size_t at = r.err.find("note:"); at != std::string::npos;
             at = r.err.find("note:", at + 1))
            ++notes;
        EXPECT_EQ(notes, 1u) << test::describe(r);
        if (cmd == "validate") {
            EXPECT_TRUE(contains(r.out, "bend       not modelled")) << test::describe(r);
        }
    }
    // run's --quiet silences the note, though it comes after the --set options.
    const ProcessResult quiet =
        runProcess({kExe, "run", kGoodScene.string(), "--set", "springs.bend=100", "--set",
                    "springs.bend=0", "--steps", "1", "--quiet"},
                   kTimeout);
    EXPECT_EQ(quiet.exitCode, 0) << test::describe(quiet);
    EXPECT_FALSE(contains(quiet.err, "note:")) << test::describe(quiet);
    // Both spellings of a list entry are one key.
    const ProcessResult same =
        runProcess({kExe, "validate", kGoodScene.string(), "--set", "colliders.1.radius=0.4",
                    "--set", "colliders[1].radius=0.5"},
                   kTimeout);
    EXPECT_EQ(same.exitCode, 0) << test::describe(same);
    EXPECT_TRUE(contains(same.err, "colliders")) << test::describe(same);
    // Different keys: nothing to say.
    const ProcessResult distinct = runProcess(
        {kExe, "validate", kGoodScene.string(), "--set", "springs.bend=1", "--set", "damping=1"},
        kTimeout);
    EXPECT_EQ(distinct.exitCode, 0) << test::describe(distinct);
    EXPECT_EQ(distinct.err, "") << test::describe(distinct);
}

// ---- files that are not scene files, and bad arguments -----------------------------------

TEST(BadPath, NonexistentFile) {
    const std::string path = (kBadDir / "no_such_scene.json").string();
    expectInvalidInput(runProcess({kExe, "validate", path}, kTimeout), path, {});
    expectInvalidInput(runProcess({kExe, "run", path, "--steps", "1"}, kTimeout), path, {});
}

TEST(BadPath, DirectoryInsteadOfFile) {
    const std::string path = kBadDir.string();
    expectInvalidInput(runProcess({kExe, "validate", path}, kTimeout), path, {});
    expectInvalidInput(runProcess({kExe, "run", path, "--steps", "1"}, kTimeout), path, {});
}

TEST(BadPath, UnreadableFile) {
    if (geteuid() == 0) GTEST_SKIP() << "root reads any file";
    const fs::path path =
        fs::temp_directory_path() / ("clothsim_unreadable_" + std::to_string(getpid()) + ".json");
    fs::copy_file(kGoodScene, path, fs::copy_options::overwrite_existing);
    chmod(path.c_str(), 0);
    expectInvalidInput(runProcess({kExe, "validate", path.string()}, kTimeout), path.string(), {});
    fs::remove(path);
}

TEST(BadArguments, ExitTwo) {
    const std::string scene = kGoodScene.string();
    const std::vector<std::vector<std::string>> cases = {
        {kExe, "run"},
        {kExe, "validate"},
        {kExe, "run", scene, "--steps", "abc"},
        {kExe, "run", scene, "--steps", "-1"},
        {kExe, "run", scene, "--steps"},
        {kExe, "run", scene, "--set"},
        {kExe, "run", scene, "--no-such-option"},
        {kExe, "run", scene, "--backend", "abacus"},
        {kExe, "run", scene, "--precision", "half"},
        // A value forgotten: the next flag is not taken as a file named "--quiet", nor '' as
        // "no output"; a count past an int is not cut to another count.
        {kExe, "run", scene, "--steps", "3", "--out-csv", "--quiet"},
        {kExe, "run", scene, "--steps", "3", "--out-csv", ""},
        {kExe, "run", scene, "--steps", "3", "--out-csv="},
        {kExe, "run", scene, "--steps", "3", "--threads", "4294967297"},
        {kExe, "run", scene, "--steps", "3", "--set", "name=\"" + std::string(300, 'a') + "\""},
    };
    for (const auto& argv : cases) {
        const ProcessResult r = runProcess(argv, kTimeout);
        std::string line;
        for (const auto& a : argv) line += (a.size() > 40 ? a.substr(0, 40) + "…" : a) + " ";
        SCOPED_TRACE(line);
        ASSERT_FALSE(r.crashed) << test::describe(r);
        EXPECT_EQ(r.exitCode, 2) << test::describe(r);
        EXPECT_FALSE(r.err.empty()) << "no message";
        EXPECT_LT(r.err.size(), 400u) << "a message that quotes a whole bad value";
    }
    const ProcessResult r = runProcess({kExe, "run", scene, "--out-csv", "--quiet"}, kTimeout);
    EXPECT_NE(r.err.find("'--quiet' is the next option"), std::string::npos) << r.err;
}

// The duration's count of steps is checked where the duration is used: past 1e12 steps a run
// without --steps is exit 2 naming duration; with --steps it runs.
TEST(BadArguments, TheDurationsStepsAreCheckedOnlyWhereTheDurationIsUsed) {
    const std::string scene = kGoodScene.string();
    ProcessResult r = runProcess(
        {kExe, "run", scene, "--set", "duration=1e9", "--set", "integrator.dt=1e-5"}, kTimeout);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find("duration: needs more than 1e12 steps"), std::string::npos) << r.err;
    r = runProcess({kExe, "run", scene, "--set", "duration=1e9", "--set", "integrator.dt=1e-5",
                    "--steps", "3", "--quiet"},
                   kTimeout);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
}

// The GPU computes in float: asking it for double is refused naming --precision (in either
// order of the flags, for run and render), never computed in float silently; float is accepted.
TEST(BadArguments, GpuInDoubleIsRefused) {
    const std::string scene = kGoodScene.string();
    const std::string png = (fs::temp_directory_path() / "clothsim_gpu_double.png").string();
    const std::vector<std::vector<std::string>> cases = {
        {kExe, "run", scene, "--backend", "gpu", "--precision", "double", "--steps", "2"},
        {kExe, "run", scene, "--precision", "double", "--backend", "gpu", "--steps", "2"},
        {kExe, "render", scene, "--backend", "gpu", "--precision", "double", "--png", png},
    };
    for (const auto& argv : cases) {
        const ProcessResult r = runProcess(argv, kTimeout);
        EXPECT_EQ(r.exitCode, 2) << argv[1] << ": " << test::describe(r);
        EXPECT_NE(r.err.find("--precision"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("float"), std::string::npos) << r.err;
    }
    const ProcessResult ok = runProcess(
        {kExe, "run", scene, "--backend", "gpu", "--precision", "float", "--steps", "2"}, kTimeout);
    EXPECT_NE(ok.exitCode, 2) << test::describe(ok);  // 0, or 4 where no GPU context exists
}

// vbd is an integrator like the others on the command line: `--set integrator.method="vbd"`
// runs on the CPU and on the GPU (exit 4 only where no GPU context exists), never exit 2.
TEST(BadArguments, VbdRunsOnBothBackends) {
    const std::string scene = CLOTH_SOURCE_DIR "/scenes/drape.json";
    for (const char* backend : {"cpu", "gpu"}) {
        const ProcessResult r = runProcess({kExe, "run", scene, "--backend", backend, "--set",
                                            "integrator.method=\"vbd\"", "--steps", "2"},
                                           kTimeout);
        if (std::string(backend) == "gpu" && r.exitCode == 4) continue;
        EXPECT_EQ(r.exitCode, 0) << backend << ": " << test::describe(r);
        EXPECT_NE(r.out.find("drape: 2 steps"), std::string::npos) << backend << ": " << r.out;
    }
}

// ---- huge resolutions are refused before anything is allocated ---------------------------

TEST(HugeResolution, RefusedBeforeAllocation) {
    // AddressSanitizer maps terabytes of shadow memory at start, so no process of such a build
    // starts under an address-space limit; the Release build runs this test.
    if (test::kAddressSanitized)
        GTEST_SKIP() << "an AddressSanitizer build cannot run under an address-space limit";
    // 1 GiB of address space: enough to start clothsim (the good scene proves it), far too
    // little for any of these grids, so an allocation attempt would end in exit 1 or a crash.
    test::ProcessOptions limited;
    limited.timeoutSeconds = kTimeout;
    limited.addressSpaceLimit = std::uint64_t(1) << 30;
    const ProcessResult ok =
        runProcess({kExe, "run", kGoodScene.string(), "--steps", "1", "--quiet"}, limited);
    ASSERT_EQ(ok.exitCode, 0) << "clothsim does not start under the limit\n" << test::describe(ok);
    for (const char* file : {"resolution_huge.json", "resolution_int_max.json",
                             "resolution_int_overflow.json", "resolution_beyond_int.json"}) {
        SCOPED_TRACE(file);
        const std::string path = (kBadDir / file).string();
        for (const auto& argv : {std::vector<std::string>{kExe, "validate", path},
                                 std::vector<std::string>{kExe, "run", path, "--quiet"}}) {
            const ProcessResult r = runProcess(argv, limited);
            expectInvalidInput(r, path, {"cloth.resolution"});
            EXPECT_LT(r.seconds, 5.0) << argv[1] << " took " << r.seconds << " s";
        }
    }
}

}  // namespace
}  // namespace cloth
