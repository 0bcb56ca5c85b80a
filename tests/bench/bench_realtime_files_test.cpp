// `clothsim bench realtime`'s output files: each form of the cloth writes its own.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;

// The per-vertex form's files sit beside the material's (realtime_cotton_per_vertex.*), so that a
// run of each form in one folder keeps both.
TEST(BenchRealtime, ThePerVertexFormWritesFilesOfItsOwn) {
    const fs::path d = test::freshTempDir("bench_realtime", "per_vertex");
    const auto r = runProcess(
        {kExe, "bench", "realtime", "--form", "per-vertex", "--backend", "cpu", "--methods",
         "symplectic_euler", "--sizes", "8", "--time", "0.05", "--no-error", "--out", d},
        120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    EXPECT_TRUE(fs::exists(d / "realtime_cotton_per_vertex.csv")) << r.out;
    EXPECT_FALSE(fs::exists(d / "realtime_cotton.csv")) << r.out;
}

}  // namespace
}  // namespace cloth
