// DESIGN.md §2's strain check during a run, not only at its end: a large step is checked at
// least every 0.1 s of simulated time (solver/instability.h strainCheckSteps).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/instability.h"
#include "support/process.h"

namespace cloth {
namespace {

TEST(StrainCheck, LargeStepsAreCheckedEveryTenthOfASecond) {
    EXPECT_EQ(strainCheckSteps(1.0 / 60), 6);
    EXPECT_EQ(strainCheckSteps(0.1), 1);
    EXPECT_EQ(strainCheckSteps(0.5), 1);
    EXPECT_EQ(strainCheckSteps(4e-4), 250);
    EXPECT_EQ(strainCheckSteps(1e-5), kStrainCheckSteps);
    EXPECT_TRUE(strainCheckDue(0, 6, 60, 6));
    EXPECT_FALSE(strainCheckDue(0, 5, 60, 6));
    EXPECT_TRUE(strainCheckDue(55, 60, 60, 6));  // the end
}

// vbd with 10 sweeps at Δt = 1/60 and without the translation's levels (which hold it) lets a
// 128² cotton sheet falling onto a sphere stretch its
// springs at the apex past max_strain = 1 (1.77 by step 25) and contract again by step 60: a run
// checked at its end only reported success. It must stop with exit 3 and name the steps.
TEST(StrainCheck, ASheetTornMidRunIsUnstableThoughItsEndIsNot) {
    const std::string scene =
        R"({"name": "apex", "cloth": {"resolution": [128, 128], "size": [1, 1],)"
        R"( "origin": [-0.5, 0.8, -0.5], "u_axis": [1, 0, 0], "v_axis": [0, 0, 1]},)"
        R"( "material": {"preset": "cotton"},)"
        R"( "integrator": {"method": "vbd", "dt": 0.016667, "iterations": 10,)"
        R"( "translation_levels": 0},)"
        R"( "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]},)"
        R"( {"type": "sphere", "center": [0, 0.25, 0], "radius": 0.25}], "duration": 1})";
    const std::filesystem::path file = std::filesystem::temp_directory_path() /
                                       ("clothsim_apex_" + std::to_string(getpid()) + ".json");
    std::ofstream(file) << scene;
    const test::ProcessResult r = test::runProcess(
        {CLOTH_EXE, "run", file.string(), "--precision", "float", "--threads", "2"}, 120);
    std::filesystem::remove(file);
    EXPECT_EQ(r.exitCode, 3) << r.err;
    EXPECT_NE(r.err.find("unstable between steps"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("> max_strain 1"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cloth
