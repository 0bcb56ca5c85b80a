// What `run` says when implicit Euler's conjugate gradient misses its tolerance: a solve cut off
// at integrator.max_iterations is told apart from one that broke down (p·A p not positive or a
// sum not finite, which a positive definite A leaves to a non-finite preconditioner output or
// state). Neither is silent, and each names its own remedy. And CLOTH_MULTIGRID_TRACE, which says
// where the GPU's V-cycle went non-finite.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/gl_required.h"
#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kDrape = CLOTH_SOURCE_DIR "/scenes/drape.json";

std::vector<std::string> implicitDrape(const std::string& preconditioner, int maxIterations) {
    return {kExe,
            "run",
            kDrape,
            "--steps",
            "3",
            "--set",
            "cloth.resolution=[16,16]",
            "--set",
            "integrator={\"method\":\"implicit_euler\",\"dt\":0.016667,\"preconditioner\":\"" +
                preconditioner + "\",\"max_iterations\":" + std::to_string(maxIterations) + "}"};
}

bool says(const std::string& text, const std::string& what) {
    return text.find(what) != std::string::npos;
}

// A copy of shaders/ in a fresh temporary folder with `kernel` changed by `edit`; empty if
// `edit` found nothing to change (the kernel changed: update the test).
fs::path brokenShaders(const std::string& kernel, const std::function<bool(std::string&)>& edit) {
    const fs::path dir =
        fs::temp_directory_path() / ("clothsim_broken_shaders_" + std::to_string(getpid()));
    fs::remove_all(dir);
    fs::copy(CLOTH_SOURCE_DIR "/shaders", dir, fs::copy_options::recursive);
    const fs::path file = dir / "compute" / kernel;
    std::stringstream source;
    source << std::ifstream(file).rdbuf();
    std::string text = source.str();
    if (!edit(text)) return {};
    std::ofstream(file) << text;
    return dir;
}

// Every count of "not finite: …" in the trace, in order.
std::vector<long> notFiniteCounts(const std::string& trace) {
    static const std::regex kCount(
        R"((\d+) (in the stencil|in the line factors|in r, z, t)|not finite: (\d+))");
    std::vector<long> counts;
    for (auto it = std::sregex_iterator(trace.begin(), trace.end(), kCount);
         it != std::sregex_iterator(); ++it)
        counts.push_back(std::stol((*it)[1].matched ? (*it)[1].str() : (*it)[3].str()));
    return counts;
}

// A cap of one iteration: every solve stops there, and the warning says the cap, not a breakdown.
TEST(SolveReport, ACappedSolveNamesTheCap) {
    const auto r = runProcess(implicitDrape("jacobi", 1), 60);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(says(r.err, "3 of 3 implicit solves stopped at integrator.max_iterations = 1"))
        << r.err;
    EXPECT_FALSE(says(r.err, "broke down")) << r.err;

    // render steps the same solver and says the same (it said nothing before).
    std::vector<std::string> argv = implicitDrape("jacobi", 1);
    argv[1] = "render";
    const fs::path png =
        fs::temp_directory_path() / ("solve_report_" + std::to_string(getpid()) + ".png");
    argv.insert(argv.end(), {"--png", png.string()});
    const auto rendered = runProcess(argv, 60);
    fs::remove(png);
    CLOTH_SKIP_IF_NO_GL(rendered);
    ASSERT_EQ(rendered.exitCode, 0) << test::describe(rendered);
    EXPECT_TRUE(
        says(rendered.err, "3 of 3 implicit solves stopped at integrator.max_iterations = 1"))
        << rendered.err;
}

// The GPU's V-cycle made to return NaN (a copy of shaders/ with cg_preconditioned.comp's z
// replaced): every solve stops before its first iteration. The run says so as a breakdown, with
// the step and the remedy, and not as the cap; the same scene with the shipped shaders says
// nothing. (NVIDIA's H100 and H200 stopped this way on a stiff 128² drape: docs/performance.md.)
TEST(SolveReport, ABrokenDownSolveIsNotCalledTheCap) {
    std::vector<std::string> argv = implicitDrape("multigrid", 3000);
    argv.insert(argv.end(), {"--backend", "gpu"});
    const auto clean = runProcess(argv, 120);
    CLOTH_SKIP_IF_NO_GL(clean);
    ASSERT_EQ(clean.exitCode, 0) << test::describe(clean);
    EXPECT_FALSE(says(clean.err, "implicit solves")) << clean.err;

    const fs::path dir = brokenShaders("cg_preconditioned.comp", [](std::string& text) {
        const std::size_t at = text.find("vec3 r = cgResidual[k].xyz, z = ");
        if (at == std::string::npos) return false;
        text.insert(text.find('\n', at) + 1, "        z = vec3(uintBitsToFloat(0x7fc00000u));\n");
        return true;
    });
    ASSERT_FALSE(dir.empty()) << "cg_preconditioned.comp changed: update this test";

    argv.insert(argv.begin(), {"/usr/bin/env", "CLOTH_SHADER_DIR=" + dir.string()});
    const auto broken = runProcess(argv, 120);
    fs::remove_all(dir);
    ASSERT_EQ(broken.exitCode, 0) << test::describe(broken);
    EXPECT_TRUE(says(broken.err, "3 of 3 implicit solves broke down")) << broken.err;
    EXPECT_TRUE(says(broken.err, "(first at step 1)")) << broken.err;
    EXPECT_TRUE(says(broken.err, "integrator.preconditioner = \"jacobi\" or --backend cpu"))
        << broken.err;
    EXPECT_FALSE(says(broken.err, "max_iterations")) << broken.err;
    EXPECT_TRUE(says(broken.out, "0.0 iterations on average")) << broken.out;
}

// Block-Jacobi's own breakdown (a membrane of 1e20 N/m: in float its 3×3 diagonal blocks invert
// to inf) names another remedy than block-Jacobi, which the other preconditioners' breakdowns
// are told to try.
TEST(SolveReport, ABlockJacobiBreakdownIsNotToldToTryBlockJacobi) {
    std::vector<std::string> argv = implicitDrape("jacobi", 3000);
    argv.insert(argv.end(), {"--set", "material.stretch=1e20", "--precision", "float"});
    const auto r = runProcess(argv, 120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(says(r.err, "3 of 3 implicit solves broke down")) << r.err;
    EXPECT_TRUE(says(r.err, "Try a smaller integrator.dt or softer springs")) << r.err;
    EXPECT_FALSE(says(r.err, "integrator.preconditioner = \"jacobi\"")) << r.err;
}

// CLOTH_MULTIGRID_TRACE=1 sums up the GPU's multigrid hierarchy after the first V-cycle, one line
// a level (16²: 16, 9 and 5 on a side) and the coarsest grid's factor: every value finite on the
// shipped shaders. With the line factors given a non-finite entry (a copy of shaders/ with one
// written into every line's band), the trace counts it in the line factors of every level with
// lines and in the vectors the sweeps made from it.
TEST(SolveReport, TheMultigridTraceShowsWhereTheHierarchyWentNonFinite) {
    std::vector<std::string> argv = implicitDrape("multigrid", 3000);
    argv.insert(argv.end(), {"--backend", "gpu"});
    argv.insert(argv.begin(), {"/usr/bin/env", "CLOTH_MULTIGRID_TRACE=1"});
    const auto clean = runProcess(argv, 120);
    CLOTH_SKIP_IF_NO_GL(clean);
    ASSERT_EQ(clean.exitCode, 0) << test::describe(clean);
    for (const char* level : {"level 0, 16x16", "level 1, 9x9", "level 2, 5x5",
                              "coarsest grid's dense factor (75 unknowns)"})
        EXPECT_TRUE(says(clean.err, level)) << level << " in:\n" << clean.err;
    const std::vector<long> counts = notFiniteCounts(clean.err);
    EXPECT_EQ(counts.size(), 3u * 3u + 1u) << clean.err;
    for (long c : counts) EXPECT_EQ(c, 0) << clean.err;

    // The band's first slot (left of the line's start: 0 otherwise) made NaN after the factor.
    const fs::path dir = brokenShaders("mg_lines.comp", [](std::string& text) {
        const std::size_t end = text.rfind('}');
        if (end == std::string::npos) return false;
        text.insert(end, "    mgWork[f] = double(uintBitsToFloat(0x7fc00000u));\n");
        return true;
    });
    ASSERT_FALSE(dir.empty());
    std::vector<std::string> broken = argv;
    broken.insert(broken.begin() + 1, "CLOTH_SHADER_DIR=" + dir.string());
    const auto r = runProcess(broken, 120);
    fs::remove_all(dir);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    const std::vector<long> bad = notFiniteCounts(r.err);
    ASSERT_EQ(bad.size(), 3u * 3u + 1u) << r.err;
    EXPECT_GT(bad[1], 0) << "level 0's line factors:\n" << r.err;
    EXPECT_GT(bad[4], 0) << "level 1's line factors:\n" << r.err;
    EXPECT_GT(bad[2], 0) << "level 0's vectors:\n" << r.err;
    EXPECT_EQ(bad[0], 0) << "level 0's stencil:\n" << r.err;
}

}  // namespace
}  // namespace cloth
