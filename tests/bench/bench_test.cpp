// clothsim bench accuracy|stability (DESIGN.md §5): the CSV's columns and rows, the reference's
// convergence report, the measured explicit-Euler bound against its closed form, plots without
// gnuplot, and bad flags.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "model/scene.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kScenes = CLOTH_SOURCE_DIR "/scenes/";

fs::path tempDir(const std::string& name) {
    return test::freshTempDir("bench_test", name);
}

struct Csv {
    std::vector<std::string> comments, columns;
    std::vector<std::map<std::string, std::string>> rows;
};

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    return cells;
}

Csv readCsv(const fs::path& path) {
    Csv csv;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("#", 0) == 0) {
            csv.comments.push_back(line);
        } else if (csv.columns.empty()) {
            csv.columns = split(line);
        } else {
            const auto cells = split(line);
            EXPECT_EQ(cells.size(), csv.columns.size()) << line;
            std::map<std::string, std::string> row;
            for (size_t i = 0; i < cells.size() && i < csv.columns.size(); ++i)
                row[csv.columns[i]] = cells[i];
            csv.rows.push_back(row);
        }
    }
    return csv;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Where gnuplot is installed, the plots must come out (a broken script fails here); without it
// the command says so and writes the CSV alone.
void expectPlots(const test::ProcessResult& r, const fs::path& dir,
                 const std::vector<std::string>& stems) {
    const bool gnuplot = runProcess({"/bin/sh", "-c", "command -v gnuplot"}, 10).exitCode == 0;
    for (const std::string& stem : stems)
        for (const char* ext : {".png", ".svg"}) {
            const fs::path file = dir / (stem + ext);
            if (gnuplot) {
                EXPECT_TRUE(fs::exists(file) && fs::file_size(file) > 1000) << file << r.err;
            } else {
                EXPECT_FALSE(fs::exists(file)) << file;
            }
        }
    EXPECT_FALSE(contains(r.err, "failed")) << r.err;
    if (!gnuplot) {
        EXPECT_TRUE(contains(r.err, "gnuplot is not installed")) << r.err;
    }
}

TEST(BenchAccuracy, QuickRunOnTheSpringWritesEveryRunWithUnitsInTheHeader) {
    const fs::path d = tempDir("accuracy");
    const auto r = runProcess({kExe, "bench", "accuracy", kScenes + "spring.json", "--quick",
                               "--backend", "cpu", "--out", d.string()},
                              120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const Csv csv = readCsv(d / "accuracy_spring.csv");
    for (const char* c :
         {"target", "method", "dt_s", "steps", "status", "pos_rms_err_rel", "pos_max_err_rel",
          "strain_err", "energy_drift_J", "wall_per_sim_s", "wall_per_step_s"})
        EXPECT_NE(std::find(csv.columns.begin(), csv.columns.end(), c), csv.columns.end()) << c;
    // integrators × rungs × (cpu double, cpu float)
    EXPECT_EQ(csv.rows.size(), std::size(kMethods) * 3u * 2u);
    for (const auto& row : csv.rows) {
        EXPECT_TRUE(row.at("status") == "stable" || row.at("status") == "unstable");
        if (row.at("status") == "stable") {
            EXPECT_FALSE(row.at("pos_rms_err_rel").empty());
        }
        EXPECT_GT(std::stod(row.at("dt_s")), 0);
    }
    expectPlots(r, d, {"accuracy_spring"});
}

TEST(BenchAccuracy, ReportsTheReferenceHalvingCheck) {
    const fs::path d = tempDir("reference");
    const auto r =
        runProcess({kExe, "bench", "accuracy", kScenes + "spring.json", "--quick", "--backend",
                    "cpu", "--methods", "explicit_euler", "--dt", "0.01", "--out", d.string()},
                   120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(contains(r.out, "reference: rk4 cpu double, dt = ")) << r.out;
    EXPECT_TRUE(contains(r.out, "halving dt changed the positions by ")) << r.out;
    EXPECT_TRUE(contains(r.out, "(< 1e-09: converged)")) << r.out;
    const Csv csv = readCsv(d / "accuracy_spring.csv");
    ASSERT_EQ(csv.comments.size(), 2u);
    EXPECT_TRUE(contains(csv.comments[1], "halving dt changed the positions by"));
    ASSERT_EQ(csv.rows.size(), 2u);  // cpu double and float, one dt
    EXPECT_EQ(csv.rows[0].at("dt_s"), "0.01");
}

// The 1×2 spring with its top vertex pinned has one mode, λ = K: explicit Euler is stable iff
// Δt < μ/K (docs/physics.md), whatever the mass.
TEST(BenchStability, ExplicitEulerOnTheSpringMeetsMuOverK) {
    const fs::path d = tempDir("stability");
    const auto r =
        runProcess({kExe, "bench", "stability", kScenes + "spring.json", "--backend", "cpu",
                    "--methods", "explicit_euler", "--sweeps", "stiffness,damping", "--stiffness",
                    "100,4000", "--damping", "0.2,2", "--out", d.string()},
                   120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const Csv csv = readCsv(d / "stability_spring.csv");
    ASSERT_EQ(csv.rows.size(), 4u);
    for (const auto& row : csv.rows) {
        const double k = std::stod(row.at("k_structural_N_per_m"));
        const double mu = std::stod(row.at("damping_Ns_per_m"));
        EXPECT_EQ(row.at("status"), "bounded");
        EXPECT_NEAR(std::stod(row.at("measured_dt_s")), mu / k, 0.1 * mu / k)
            << row.at("sweep") << " K = " << k << ", mu = " << mu;
        EXPECT_NEAR(std::stod(row.at("predicted_tight_dt_s")), mu / k, 1e-9);
    }
    expectPlots(r, d, {"stability_spring", "stability_damping_spring"});
}

TEST(BenchStability, ImplicitEulerIsReportedStableToTheCap) {
    const fs::path d = tempDir("cap");
    const auto r = runProcess({kExe, "bench", "stability", kScenes + "spring.json", "--backend",
                               "cpu", "--methods", "implicit_euler", "--sweeps", "stiffness",
                               "--stiffness", "100", "--cap", "0.05", "--out", d.string()},
                              120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const Csv csv = readCsv(d / "stability_spring.csv");
    ASSERT_EQ(csv.rows.size(), 1u);
    EXPECT_EQ(csv.rows[0].at("predicted_tight_dt_s"), "");  // no predicted bound
    EXPECT_EQ(csv.rows[0].at("status"), "stable_to_cap");
    EXPECT_EQ(csv.rows[0].at("measured_dt_s"), "0.05");
}

TEST(BenchPlots, WithoutGnuplotTheCsvIsStillWrittenAndTheReasonSaid) {
    const fs::path d = tempDir("nognuplot");
    const auto r = runProcess({"/usr/bin/env", "PATH=/nonexistent", kExe, "bench", "stability",
                               kScenes + "spring.json", "--quick", "--backend", "cpu", "--methods",
                               "explicit_euler", "--sweeps", "stiffness", "--out", d.string()},
                              120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(contains(r.err, "gnuplot is not installed")) << r.err;
    EXPECT_TRUE(fs::exists(d / "stability_spring.csv"));
    EXPECT_FALSE(fs::exists(d / "stability_spring.png"));
}

TEST(BenchHelp, BenchAndBothBenchmarksHaveHelp) {
    for (std::vector<std::string> argv : {std::vector<std::string>{kExe, "bench", "--help"},
                                          {kExe, "bench", "accuracy", "--help"},
                                          {kExe, "bench", "stability", "--help"},
                                          {kExe, "bench", "speed", "--help"}}) {
        const auto r = runProcess(argv, 60);
        EXPECT_EQ(r.exitCode, 0) << argv.back();
        EXPECT_TRUE(contains(r.out, "usage: clothsim bench")) << r.out;
    }
    const auto bench = runProcess({kExe, "bench", "--help"}, 60);
    EXPECT_FALSE(contains(bench.out, "not built yet")) << bench.out;
}

TEST(BenchArgs, BadInputExitsTwoNamingTheFlag) {
    const std::string spring = kScenes + "spring.json";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"accuracy", spring, "--methods", "euler"}, "--methods"},
        {{"accuracy", spring, "--methods", "rk4,"}, "--methods"},
        {{"accuracy", spring, "--dt", "0.01,abc"}, "--dt"},
        {{"accuracy", spring, "--dt", "-0.01"}, "--dt"},
        {{"accuracy", spring, "--dt", ""}, "--dt"},
        {{"accuracy", spring, "--dt", "1e-300"}, "--dt"},  // 5e299 steps
        {{"accuracy", spring, "--time", "0"}, "--time"},
        {{"accuracy", spring, "--backend", "tpu"}, "--backend"},
        {{"accuracy", spring, "--bogus"}, "--bogus"},
        {{"accuracy", spring, "--set", "springs.structural=-1"}, "springs.structural"},
        {{"accuracy"}, "SCENE"},
        {{"accuracy", "/nonexistent/scene.json"}, "/nonexistent/scene.json"},
        {{"stability", spring, "--sweeps", "temperature"}, "--sweeps"},
        {{"stability", spring, "--stiffness", "1e3,0"}, "--stiffness"},
        {{"stability", spring, "--max-steps", "-5"}, "--max-steps"},
        {{"stability"}, "SCENE"},
        {{"frobnicate"}, "frobnicate"},
        {{}, "bench"},
    };
    for (const auto& [args, flag] : cases) {
        std::vector<std::string> argv{kExe, "bench"};
        argv.insert(argv.end(), args.begin(), args.end());
        const auto r = runProcess(argv, 60);
        const std::string what = args.empty() ? "bench" : args[0] + " " + flag;
        EXPECT_EQ(r.exitCode, 2) << what << "\n" << test::describe(r);
        EXPECT_TRUE(contains(r.err, "invalid input")) << what << "\n" << r.err;
        EXPECT_TRUE(contains(r.err, flag)) << what << "\n" << r.err;
    }
}

}  // namespace
}  // namespace cloth
