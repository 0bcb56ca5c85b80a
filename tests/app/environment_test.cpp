// The environment variables the app reads (README, "Environment") and hands to the libraries as
// options: each one takes effect, and a bad value is exit 2 naming the variable.
#include <gtest/gtest.h>

#include "support/process.h"

namespace cloth {
namespace {

using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kSpring = CLOTH_SOURCE_DIR "/scenes/spring.json";

test::ProcessResult runWith(const std::string& assignment, std::vector<std::string> args) {
    std::vector<std::string> argv{"/usr/bin/env", assignment, kExe};
    argv.insert(argv.end(), args.begin(), args.end());
    return runProcess(argv, 60);
}

TEST(Environment, CpuIsaPicksTheRowKernelsTheRunReports) {
    const auto r = runWith("CLOTH_CPU_ISA=generic", {"run", kSpring, "--steps", "10"});
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_NE(r.out.find("generic"), std::string::npos) << r.out;
    const auto s = runWith("CLOTH_CPU_ISA=scalar", {"run", kSpring, "--steps", "10"});
    ASSERT_EQ(s.exitCode, 0) << test::describe(s);
    EXPECT_NE(s.out.find("scalar"), std::string::npos) << s.out;
}

TEST(Environment, BadValuesAreInvalidInputNamingTheVariable) {
    for (const auto& [assignment, name] :
         {std::pair{"CLOTH_CPU_ISA=avx-512", "CLOTH_CPU_ISA"},
          {"CLOTH_WORKGROUP=abc", "CLOTH_WORKGROUP"},
          {"CLOTH_EGL_DEVICE=first", "CLOTH_EGL_DEVICE"},
          {"CLOTH_MULTIGRID_TRACE=yes", "CLOTH_MULTIGRID_TRACE"},
          {"CLOTH_MULTIGRID_CHUNKS=4", "CLOTH_MULTIGRID_CHUNKS"},
          {"CLOTH_MULTIGRID_CHUNKS=33", "CLOTH_MULTIGRID_CHUNKS"}}) {
        const auto r = runWith(assignment, {"run", kSpring, "--steps", "10"});
        EXPECT_EQ(r.exitCode, 2) << assignment << ": " << test::describe(r);
        EXPECT_NE(r.err.find(name), std::string::npos) << assignment << ": " << r.err;
    }
}

TEST(Environment, WorkGroupReachesTheGpuVariantThatValidatePrints) {
    const auto r = runWith("CLOTH_WORKGROUP=8x4", {"validate", kSpring});
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    if (r.out.find("built without the GPU backend") != std::string::npos)
        GTEST_SKIP() << "this build has no GPU backend (CLOTH_GPU=OFF)";
    EXPECT_NE(r.out.find("WX=8 WY=4"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace cloth
