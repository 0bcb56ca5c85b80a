// clothsim bench speed: the CSV's and JSON's columns, a baseline row per size, positive speed-ups
// and bandwidths, bytes per vertex as the model computes them, bad flags, the Debug refusal.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench/bench_speed_model.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;

fs::path tempDir(const std::string& name) {
    return test::freshTempDir("speed_test", name);
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    if (!line.empty() && line.back() == ',') cells.push_back("");
    return cells;
}

std::vector<std::map<std::string, std::string>> readRows(const fs::path& path,
                                                         std::vector<std::string>& columns) {
    std::vector<std::map<std::string, std::string>> rows;
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("#", 0) == 0) continue;
        if (columns.empty()) {
            columns = split(line);
            continue;
        }
        const auto cells = split(line);
        EXPECT_EQ(cells.size(), columns.size()) << line;
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < cells.size() && i < columns.size(); ++i) row[columns[i]] = cells[i];
        rows.push_back(row);
    }
    return rows;
}

TEST(BenchSpeed, QuickRunWritesCsvAndJsonWithBaselinePerSize) {
    const fs::path d = tempDir("quick");
    const auto r = runProcess({kExe, "bench", "speed", "--sizes", "16,32", "--quick", "--out",
                               d.string(), "--label", "t"},
                              300);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::vector<std::string> columns;
    const auto rows = readRows(d / "speed_t.csv", columns);
    for (const char* c :
         {"size", "vertices", "target", "method", "ms_per_step", "device_ms_per_step",
          "timing_source", "steps_per_s", "vertex_steps_per_s", "min_bytes_per_step",
          "achieved_GB_per_s", "bandwidth_fraction", "speedup", "bytes_per_vertex"})
        EXPECT_NE(std::find(columns.begin(), columns.end(), c), columns.end()) << c;
    std::map<std::string, int> baselines, gpuRows;
    bool cpuDouble = false;
    for (const auto& row : rows) {
        if (row.at("target") == "baseline") {
            ++baselines[row.at("size")];
            EXPECT_EQ(std::stod(row.at("speedup")), 1.0);
            EXPECT_EQ(std::stod(row.at("bytes_per_vertex")), double(app::kBaselineBytesPerVertex));
        }
        EXPECT_GT(std::stod(row.at("speedup")), 0) << row.at("target");
        EXPECT_GT(std::stod(row.at("achieved_GB_per_s")), 0);
        EXPECT_GT(std::stod(row.at("vertex_steps_per_s")), 0);
        if (row.at("target") == "cpu_double") {
            cpuDouble = true;
            EXPECT_EQ(std::stod(row.at("bytes_per_vertex")),
                      double(app::cpuBytesPerVertex(Precision::Double, Method::ExplicitEuler)));
            EXPECT_EQ(std::stod(row.at("min_bytes_per_step")),
                      96.0 * std::stod(row.at("vertices")));
        }
        if (row.at("target") == "gpu_float") {
            ++gpuRows[row.at("size")];
            EXPECT_GE(std::stod(row.at("bytes_per_vertex")), 64.0);  // 4 vec4 at least
            // As asked (auto by default) and as run: many steps per dispatch at 16² (the
            // crossover is at 24² on llvmpipe, 64² assumed on hardware).
            EXPECT_EQ(row.at("gpu_variant"), "16x16/global/auto");
            const std::string& dispatch = row.at("gpu_dispatch");
            EXPECT_TRUE(dispatch == "many-steps" ||
                        (dispatch == "per-step" && row.at("size") != "16"))
                << dispatch;
        }
    }
    EXPECT_TRUE(cpuDouble);
    EXPECT_EQ(baselines["16"], 1);
    EXPECT_EQ(baselines["32"], 1);

    std::ifstream in(d / "speed_t.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j["rows"].size(), rows.size());
    EXPECT_GT(j["cpu_triad_GB_per_s"].get<double>(), 0);
    // Where a GPU is there (the bench measured its copy bandwidth) or required (CI), every size
    // has its GPU row: the assertions on them above cannot pass by there being none.
    const char* require = std::getenv("CLOTH_REQUIRE_GPU");
    const bool gpuExpected =
        !j["gpu_copy_GB_per_s"].is_null() || (require && std::string(require) == "1");
    if (gpuExpected) {
        ASSERT_TRUE(j["gpu_copy_GB_per_s"].is_number());
        EXPECT_GT(j["gpu_copy_GB_per_s"].get<double>(), 0);
        EXPECT_EQ(gpuRows["16"], 1);
        EXPECT_EQ(gpuRows["32"], 1);
    } else {
        EXPECT_TRUE(gpuRows.empty());
    }
    EXPECT_EQ(j["build_type"], CLOTH_BUILD_TYPE);
}

TEST(BenchSpeed, BadFlagsExitTwoNamingTheFlag) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--sizes", "16,abc"}, "--sizes"},
        {{"--sizes", "1.5"}, "--sizes"},
        {{"--sizes", "0"}, "--sizes"},
        {{"--sizes", "1000000"}, "--sizes"},
        {{"--backend", "tpu"}, "--backend"},
        {{"--methods", "euler"}, "--methods"},
        {{"--features", "some"}, "--features"},
        {{"--peer", "havok"}, "--peer"},
        {{"--peer-dt", "1e-3"}, "--peer-dt"},
        {{"--peer-dt", "-1"}, "--peer-dt"},
        {{"--workgroups", "16by16"}, "--workgroups"},
        {{"--workgroups", "0x8"}, "--workgroups"},
        {{"--sizes", "16", "--workgroups", "2000x2000"}, "--workgroups: 2000x2000 exceeds"},
        // Refused before the sizes are timed (before, after them, with exit 1 for the label).
        {{"--quick", "--sizes", "16", "--backend", "cpu", "--label", "../x"}, "--label"},
        {{"--quick", "--sizes", "16", "--backend", "cpu", "--out", CLOTH_SOURCE_DIR "/README.md"},
         "--out: cannot write into directory"},
        {{"--gpu-forces", "shared"}, "--gpu-forces"},
        {{"--gpu-dispatch", "fused"}, "--gpu-dispatch"},
        {{"--check-every", "0"}, "--check-every"},
        {{"--bogus"}, "--bogus"}};
    for (const auto& [flags, name] : cases) {
        std::vector<std::string> argv{kExe, "bench", "speed"};
        argv.insert(argv.end(), flags.begin(), flags.end());
        const auto r = runProcess(argv, 60);
        EXPECT_EQ(r.exitCode, 2) << name << "\n" << r.err;
        EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    }
}

// --features both: each backend twice per size, as declared and with every feature compiled in.
TEST(BenchSpeed, FeaturesBothTimesDeclaredAndAll) {
    const fs::path d = tempDir("features");
    const auto r = runProcess({kExe, "bench", "speed", "--sizes", "16", "--quick", "--backend",
                               "cpu", "--features", "both", "--out", d.string(), "--label", "f"},
                              120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::vector<std::string> columns;
    std::map<std::string, int> count;
    for (const auto& row : readRows(d / "speed_f.csv", columns))
        ++count[row.at("target") + ":" + row.at("features")];
    for (const char* target : {"cpu_double", "cpu_float"}) {
        EXPECT_EQ(count[std::string(target) + ":declared"], 1) << target;
        EXPECT_EQ(count[std::string(target) + ":all"], 1) << target;
    }
    EXPECT_EQ(count["baseline:declared"], 1);
}

TEST(BenchSpeed, DebugBuildsAreRefusedUnlessAllowed) {
    EXPECT_TRUE(app::debugRefusal("Debug", false).has_value());
    EXPECT_FALSE(app::debugRefusal("Debug", true).has_value());
    EXPECT_FALSE(app::debugRefusal("Release", false).has_value());
    EXPECT_FALSE(app::debugRefusal("RelWithDebInfo", false).has_value());
    EXPECT_NE(app::debugRefusal("Debug", false)->find("--allow-debug"), std::string::npos);
}

TEST(BenchSpeed, SizesThatDoNotFitAreRefused) {
    EXPECT_FALSE(app::sizeRefusal(1024, std::uint64_t(1) << 30).has_value());
    EXPECT_TRUE(app::sizeRefusal(4096, std::uint64_t(1) << 30).has_value());
}

TEST(BenchSpeed, TrafficModelCountsFourVectors) {
    EXPECT_EQ(app::minStepBytesPerVertex(Backend::Cpu, Precision::Double), 96u);
    EXPECT_EQ(app::minStepBytesPerVertex(Backend::Cpu, Precision::Float), 48u);
    EXPECT_EQ(app::minStepBytesPerVertex(Backend::Gpu, Precision::Float), 64u);
}

// Explicit Euler past its stability bound (hanging: dt ≈ 2.9e-5 s, here 1e-3 s) blows up: the
// row says "unstable" with no time, the sweep and the baseline go on, and the run exits 0.
TEST(BenchSpeed, AnUnstableRunIsReportedAsARowNotAnError) {
    const fs::path d = tempDir("unstable");
    const auto r =
        runProcess({kExe, "bench", "speed", "--sizes", "16", "--backend", "cpu", "--quick", "--set",
                    "integrator.dt=1e-2", "--out", d.string(), "--label", "t"},
                   300);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.err.find("became unstable"), std::string::npos) << r.err;
    std::vector<std::string> columns;
    const auto rows = readRows(d / "speed_t.csv", columns);
    int unstable = 0;
    for (const auto& row : rows) {
        if (row.at("target") == "baseline") {
            EXPECT_EQ(row.at("status"), "ok");
            EXPECT_FALSE(row.at("vertex_steps_per_s").empty());
            continue;
        }
        EXPECT_EQ(row.at("status"), "unstable") << row.at("target");
        EXPECT_TRUE(row.at("vertex_steps_per_s").empty()) << row.at("target");
        ++unstable;
    }
    EXPECT_EQ(unstable, 2);  // cpu float and cpu double
}

}  // namespace
}  // namespace cloth
