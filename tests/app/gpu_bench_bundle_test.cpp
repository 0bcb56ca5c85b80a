// scripts/gpu-bench.sh bundle: the Release build packed to run on another machine that has only
// a C library and a GPU driver. Every shared library the executable loads, but the C library's
// own, must resolve inside the bundle, and the bundled executable must run from it.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "support/process.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::runProcess;

const std::string kExe = CLOTH_EXE;
const std::string kScript = CLOTH_SOURCE_DIR "/scripts/gpu-bench.sh";

bool cLibrary(const std::string& name) {
    for (const char* prefix :
         {"libc.so", "libm.so", "libdl.so", "libpthread.so", "librt.so", "ld-linux", "linux-vdso"})
        if (name.rfind(prefix, 0) == 0) return true;
    return false;
}

TEST(GpuBenchBundle, EveryLibraryButTheCLibraryResolvesInsideTheBundle) {
    const fs::path d = test::freshTempDir("gpu_bench", "bundle");
    const fs::path bundle = d / "bundle";
    const fs::path build = fs::path(kExe).parent_path();
    const auto packed = runProcess({kScript, "bundle", build.string(), bundle.string()}, 120);
    ASSERT_EQ(packed.exitCode, 0) << test::describe(packed);
    ASSERT_TRUE(fs::exists(bundle / "clothsim"));
    ASSERT_TRUE(fs::exists(bundle / "shaders" / "compute" / "forces.glsl"));

    const auto ldd = runProcess({"/usr/bin/env", "LD_LIBRARY_PATH=" + (bundle / "lib").string(),
                                 "ldd", (bundle / "clothsim").string()},
                                60);
    ASSERT_EQ(ldd.exitCode, 0) << test::describe(ldd);
    std::istringstream lines(ldd.out);
    std::string line;
    int bundled = 0;
    while (std::getline(lines, line)) {
        std::istringstream words(line);
        std::string name, arrow, path;
        words >> name >> arrow >> path;
        if (cLibrary(fs::path(name).filename().string())) continue;
        ASSERT_EQ(arrow, "=>") << line;
        EXPECT_NE(path, "not") << "unresolved: " << line;
        EXPECT_EQ(fs::path(path).parent_path(), bundle / "lib") << "loaded from outside: " << line;
        ++bundled;
    }
    EXPECT_GE(bundled, 2) << ldd.out;  // libstdc++ and libgcc_s at least
    for (const auto& e : fs::directory_iterator(bundle / "lib"))
        EXPECT_FALSE(cLibrary(e.path().filename().string())) << e.path();

    // The bundled executable runs from the bundle alone (its shaders there, not the source tree's).
    const auto info = runProcess({"/usr/bin/env", "LD_LIBRARY_PATH=" + (bundle / "lib").string(),
                                  "CLOTH_SHADER_DIR=" + (bundle / "shaders").string(),
                                  (bundle / "clothsim").string(), "info"},
                                 60);
    ASSERT_EQ(info.exitCode, 0) << test::describe(info);
    EXPECT_NE(info.out.find("clothsim "), std::string::npos) << info.out;
    fs::remove_all(d);
}

TEST(GpuBenchBundle, RefusesAFolderWithoutTheExecutable) {
    const fs::path d = test::freshTempDir("gpu_bench", "missing");
    const auto r =
        runProcess({kScript, "bundle", (d / "nothing").string(), (d / "b").string()}, 60);
    EXPECT_EQ(r.exitCode, 2) << test::describe(r);
    EXPECT_NE(r.err.find("no such executable"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d / "b"));
    fs::remove_all(d);
}

}  // namespace
}  // namespace cloth
