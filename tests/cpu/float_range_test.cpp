// A cloth beyond what float arithmetic can square (model/float_range.h) is an input error naming
// its key in float (the CPU in float, the GPU), where it went non-finite at its first step and was
// reported unstable; in double it runs.
#include "model/float_range.h"

#include <gtest/gtest.h>

#include <string>

#include "cpu/cpu_backend.h"
#include "model/errors.h"
#include "scene/scene_loader.h"

namespace cloth {
namespace {

Scene sheet(double size, double origin) {
    Scene s = loadScene(CLOTH_SOURCE_DIR "/scenes/hanging.json");
    s.cloth.size = {size, size};
    s.cloth.origin = {origin, 0, 0};
    return s;
}

std::string refusedKey(const Scene& s) {
    try {
        makeCpuSolver(s, {Precision::Float, 1});
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("--precision double"), std::string::npos) << e.what();
        return e.key();
    }
    return "";
}

TEST(FloatRange, AClothFloatCannotSquareIsRefusedNamingItsKeyAndRunsInDouble) {
    EXPECT_EQ(refusedKey(sheet(1e50, 0)), "cloth.size");
    EXPECT_EQ(refusedKey(sheet(1e19, 0)), "cloth.size");
    EXPECT_EQ(refusedKey(sheet(1, 1e30)), "cloth.origin");
    EXPECT_EQ(refusedKey(sheet(1e17, 1e17)), "");  // inside: accepted
    auto solver = makeCpuSolver(sheet(1e50, 0), {Precision::Double, 1});
    EXPECT_FALSE(solver->step(10).unstable);
}

}  // namespace
}  // namespace cloth
