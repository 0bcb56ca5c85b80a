// The command line of DESIGN.md §5 on valid input: run's summary and files, validate's report,
// info, --help on every subcommand (bench: tests/bench/bench_test.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kScenes = CLOTH_SOURCE_DIR "/scenes/";

fs::path tempDir(const std::string& name) {
    return test::freshTempDir("cli_test", name);
}

TEST(CliRun, PrintsOneSummaryLineWithVertexStepsPerSecond) {
    const auto r = runProcess({kExe, "run", kScenes + "hanging.json", "--steps", "200"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("hanging: 200 steps"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("vertex-steps/s"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("s simulated"), std::string::npos) << r.out;
}

TEST(CliRun, QuietPrintsNothing) {
    const auto r =
        runProcess({kExe, "run", kScenes + "spring.json", "--steps", "10", "--quiet"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "");
}

TEST(CliRun, WritesPaddedFramesEveryKStepsAndTheFinalFiles) {
    const fs::path d = tempDir("frames");
    const auto r = runProcess({kExe, "run", kScenes + "chain.json", "--steps", "50", "--frames",
                               (d / "frames").string(), "--every", "20", "--out-obj",
                               (d / "final.obj").string(), "--out-csv", (d / "final.csv").string()},
                              60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(d / "frames")) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    // Steps 0, 20, 40 (50 is not a multiple of 20).
    EXPECT_EQ(names, (std::vector<std::string>{"chain_000000.obj", "chain_000020.obj",
                                               "chain_000040.obj"}));
    EXPECT_TRUE(fs::exists(d / "final.obj"));
    std::ifstream csv(d / "final.csv");
    std::string line;
    int rows = -1;
    while (std::getline(csv, line)) ++rows;
    EXPECT_EQ(rows, 3);  // 1×3 chain
    fs::remove_all(d);
}

// Runs `clothsim run SCENE --quiet --out-csv TMP extra...` and returns the CSV's text.
std::string runToCsv(const std::string& scene, std::vector<std::string> extra) {
    // Unique per process and call: ctest runs tests side by side in separate processes.
    static int calls = 0;
    const fs::path csv =
        fs::temp_directory_path() / ("clothsim_cli_test_run_" + std::to_string(getpid()) + "_" +
                                     std::to_string(++calls) + ".csv");
    std::vector<std::string> argv = {kExe,      "run",       kScenes + scene,
                                     "--quiet", "--out-csv", csv.string()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const auto r = runProcess(argv, 60);
    EXPECT_EQ(r.exitCode, 0) << test::describe(r);
    std::ifstream in(csv);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    fs::remove(csv);
    return text;
}

TEST(CliRun, SetOverridesChangeTheRun) {
    const std::string withBend = runToCsv("hanging.json", {"--steps", "300"});
    const std::string noBend =
        runToCsv("hanging.json", {"--steps", "300", "--set", "material.bend=0"});
    EXPECT_FALSE(withBend.empty());
    EXPECT_NE(withBend, noBend);
}

TEST(CliRun, ThreadCountDoesNotChangeTheResult) {
    const std::string one = runToCsv("drape.json", {"--steps", "500", "--threads", "1"});
    EXPECT_FALSE(one.empty());
    EXPECT_EQ(one, runToCsv("drape.json", {"--steps", "500", "--threads", "2"}));
}

// drape.json is cotton (docs/physics.md "Presets"): 0.15 kg/m² over 1.2 m × 1.2 m is 0.216 kg; on
// square cells the shear springs carry G = 105 N/m and the structural ones C − G = 193.0 N/m, with
// C = (Y + √(Y² + 4G²))/2 = 298.0 N/m for Y = 261 N/m (docs/physics.md, "From a material to the
// grid").
TEST(CliValidate, ReportsWhatTheSceneModelsAndItsStableStep) {
    const auto r = runProcess({kExe, "validate", kScenes + "drape.json"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    for (const char* s :
         {"material     cotton", "0.216 kg in all", "structural K = 192.997", "shear K = 105 N/m",
          "B = 1.82e-05 N*m", "air drag c = 1 1/s", "wind not modelled", "plane through",
          "sphere at", "explicit_euler", "largest stable dt", "symplectic_euler", "verlet", "rk4",
          "implicit_euler      any (unconditional)", "power iterations", "inside the bound",
          "valid"})
        EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
}

// The step control (integrator.max_step_strain) says what it does in validate and what it did in
// run's summary; a scene without it prints neither line.
TEST(CliRun, StepControlIsReportedWhereTheSceneDeclaresIt) {
    const std::vector<std::string> control = {"--set", "integrator.max_step_strain=1e-9"};
    auto args = [&](const char* command, bool withControl) {
        std::vector<std::string> a = {kExe, command, kScenes + "hanging.json"};
        if (std::string(command) == "run") a.insert(a.end(), {"--steps", "20"});
        if (withControl) a.insert(a.end(), control.begin(), control.end());
        return a;
    };
    const auto run = runProcess(args("run", true), 60);
    ASSERT_EQ(run.exitCode, 0) << test::describe(run);
    EXPECT_NE(run.out.find("of 20 steps split (max_step_strain 1e-09)"), std::string::npos)
        << run.out;
    EXPECT_NE(run.out.find("the shortest dt/16"), std::string::npos) << run.out;
    const auto validate = runProcess(args("validate", true), 60);
    ASSERT_EQ(validate.exitCode, 0) << test::describe(validate);
    EXPECT_NE(validate.out.find("step control a step that stretches"), std::string::npos)
        << validate.out;
    for (const char* command : {"run", "validate"}) {
        const auto plain = runProcess(args(command, false), 60);
        ASSERT_EQ(plain.exitCode, 0) << test::describe(plain);
        EXPECT_EQ(plain.out.find("step control"), std::string::npos) << plain.out;
    }
}

// A key of another method's (vbd's sweeps under implicit_euler, the CG's under vbd) does nothing:
// run and validate say so in a note, naming the key and whose it is, and validate lists only the
// method's own knobs, with implicit_euler's preconditioner. The method's own keys get no note.
TEST(CliRun, AKeyOfAnotherMethodIsNoted) {
    const std::string implicit =
        "integrator={\"method\":\"implicit_euler\",\"dt\":0.01,"
        "\"preconditioner\":\"multigrid\",\"iterations\":500}";
    const auto run =
        runProcess({kExe, "run", kScenes + "hanging.json", "--steps", "2", "--set", implicit}, 60);
    ASSERT_EQ(run.exitCode, 0) << test::describe(run);
    EXPECT_NE(run.err.find("note: integrator.iterations = 500 is vbd's; implicit_euler does not "
                           "use it (the CG's cap: max_iterations)"),
              std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("preconditioner"), std::string::npos) << run.err;

    const std::string vbd =
        "integrator={\"method\":\"vbd\",\"dt\":0.01,\"iterations\":5,"
        "\"chebyshev_rho\":0.5,\"max_iterations\":50}";
    const auto validate =
        runProcess({kExe, "validate", kScenes + "hanging.json", "--set", vbd}, 60);
    ASSERT_EQ(validate.exitCode, 0) << test::describe(validate);
    EXPECT_NE(validate.err.find("note: integrator.max_iterations = 50 is implicit_euler's; vbd "
                                "does not use it (vbd's sweeps a step: iterations)"),
              std::string::npos)
        << validate.err;
    EXPECT_EQ(validate.err.find("chebyshev_rho"), std::string::npos) << validate.err;
    for (const char* listed : {"integrator.iterations = 5", "integrator.chebyshev_rho = 0.5"})
        EXPECT_NE(validate.out.find(listed), std::string::npos) << listed << "\n" << validate.out;
    EXPECT_EQ(validate.out.find("integrator.tolerance"), std::string::npos) << validate.out;
    // Passes of the translation's levels where no level runs: noted, not refused.
    const auto passes = runProcess(
        {kExe, "validate", kScenes + "hanging.json", "--set", vbd, "--set",
         "integrator.translation_levels=0", "--set", "integrator.translation_level_passes=3"},
        60);
    ASSERT_EQ(passes.exitCode, 0) << test::describe(passes);
    EXPECT_NE(passes.err.find("note: integrator.translation_level_passes = 3 repeats the "
                              "translation's levels; translation_levels = 0 runs none"),
              std::string::npos)
        << passes.err;
    // More passes than sweeps: one before each sweep, noted.
    const auto many = runProcess({kExe, "validate", kScenes + "hanging.json", "--set", vbd, "--set",
                                  "integrator.translation_level_passes=7"},
                                 60);
    ASSERT_EQ(many.exitCode, 0) << test::describe(many);
    EXPECT_NE(many.err.find("note: integrator.translation_level_passes = 7 is more than the 5 "
                            "sweeps a step: the levels run once before each sweep"),
              std::string::npos)
        << many.err;

    const auto own = runProcess({kExe, "validate", kScenes + "hanging.json", "--set", implicit,
                                 "--set", "integrator.iterations=10"},
                                60);
    ASSERT_EQ(own.exitCode, 0) << test::describe(own);
    EXPECT_EQ(own.err.find("note"), std::string::npos) << own.err;
    EXPECT_NE(own.out.find("conjugate gradient, preconditioner multigrid"), std::string::npos)
        << own.out;
    EXPECT_NE(own.out.find("integrator.tolerance = 1e-05"), std::string::npos) << own.out;
}

// validate says how many translation levels vbd runs and how wide their finest blocks are: a
// 300 × 200 sheet is wider than 256, so translation_block_width 16 adds a fifth level (blocks of
// 10 × 7); with 0, the 4 asked (19 × 13); with no levels, no line.
TEST(CliValidate, SaysTheTranslationLevelsVbdRuns) {
    const auto validate = [](const char* width) {
        return runProcess(
            {kExe, "validate", kScenes + "hanging.json", "--set",
             "integrator={\"method\":\"vbd\",\"dt\":0.01}", "--set", "cloth.resolution=[300,200]",
             "--set", std::string("integrator.translation_block_width=") + width},
            60);
    };
    const auto wide = validate("16");
    ASSERT_EQ(wide.exitCode, 0) << test::describe(wide);
    EXPECT_NE(wide.out.find("vbd runs 5 translation levels (translation_levels = 4, "
                            "translation_block_width = 16): the finest blocks 10 x 7 vertices"),
              std::string::npos)
        << wide.out;
    const auto asked = validate("0");
    EXPECT_NE(asked.out.find("vbd runs 4 translation levels (translation_levels = 4, "
                             "translation_block_width = 0): the finest blocks 19 x 13 vertices"),
              std::string::npos)
        << asked.out;
    const auto none = runProcess({kExe, "validate", kScenes + "hanging.json", "--set",
                                  "integrator={\"method\":\"vbd\",\"dt\":0.01,"
                                  "\"translation_levels\":0}"},
                                 60);
    EXPECT_EQ(none.out.find("translation levels"), std::string::npos) << none.out;
}

TEST(CliValidate, AbsentFamilyIsReportedAsNotModelled) {
    const auto r = runProcess({kExe, "validate", kScenes + "spring.json"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("shear      not modelled"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bend       not modelled"), std::string::npos) << r.out;
}

TEST(CliInfo, PrintsBuildAndGpuLines) {
    const auto r = runProcess({kExe, "info"}, 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("clothsim "), std::string::npos);
    EXPECT_NE(r.out.find("gpu"), std::string::npos);
}

TEST(CliHelp, EverySubcommandHasHelp) {
    for (const char* c : {"run", "validate", "info"}) {
        const auto r = runProcess({kExe, c, "--help"}, 60);
        EXPECT_EQ(r.exitCode, 0) << c;
        EXPECT_NE(r.out.find("usage: clothsim"), std::string::npos) << c;
    }
    const auto top = runProcess({kExe, "--help"}, 60);
    EXPECT_EQ(top.exitCode, 0);
    EXPECT_NE(top.out.find("exit codes"), std::string::npos);
    const auto none = runProcess({kExe}, 60);
    EXPECT_EQ(none.exitCode, 2);
}

TEST(CliArgs, BadArgumentsExitTwoNamingTheOption) {
    const std::vector<std::vector<std::string>> cases = {
        {"run", kScenes + "spring.json", "--steps", "-3"},
        {"run", kScenes + "spring.json", "--backend", "tpu"},
        {"run", kScenes + "spring.json", "--precision", "half"},
        {"run", kScenes + "spring.json", "--frames", "/tmp/x"},
        {"run", kScenes + "spring.json", "--bogus"},
        {"run", kScenes + "spring.json", "--out-csv", "/nonexistent-dir/x.csv"},
        {"run", kScenes + "spring.json", "--out-obj", "/tmp"},
        {"run"},
        {"frobnicate"},
    };
    for (auto c : cases) {
        c.insert(c.begin(), kExe);
        const auto r = runProcess(c, 60);
        EXPECT_EQ(r.exitCode, 2) << c[1] << " " << (c.size() > 3 ? c[3] : "") << test::describe(r);
        EXPECT_NE(r.err.find("invalid input"), std::string::npos);
    }
}

}  // namespace
}  // namespace cloth
