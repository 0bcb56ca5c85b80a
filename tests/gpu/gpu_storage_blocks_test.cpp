// GL guarantees a compute shader 8 shader storage blocks; rk4's and implicit Euler's kernels
// declare more. A device with fewer than a kernel needs is told at load, naming the kernel and
// both numbers (GpuUnavailable, exit 4), instead of failing at link time; the count the loader
// makes from the assembled text is checked against what the driver reports as active.
#include <GL/glew.h>

#include "gpu/egl_context.h"
#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "gpu/shader_loader.h"
#include "model/errors.h"

namespace cloth::test {
namespace {

constexpr const char* kShaderDir = CLOTH_SOURCE_DIR "/shaders";

// Every feature a kernel can bind a block for: all families, wind, a plane, a sphere, a box and a
// moving capsule (the Colliders block), pins (the Pins block).
Scene everyFeature(Method method) {
    Scene s = parseScene(R"({
      "name": "every feature",
      "cloth": { "resolution": [9, 7], "size": [1, 1], "origin": [0, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1] },
      "springs": { "structural": 100.0, "shear": 50.0, "bend": 10.0 },
      "damping": 0.5,
      "pins": [[0, 0]],
      "wind": { "direction": [1, 0, 0], "strength": 1.0 },
      "colliders": [ { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] },
                     { "type": "sphere", "center": [0, 0.5, 0], "radius": 0.2 },
                     { "type": "box", "center": [2, 0, 0], "half_extents": [0.1, 0.1, 0.1] },
                     { "type": "capsule", "a": [3, 0, 0], "b": [3, 1, 0], "radius": 0.1,
                       "motion": { "type": "linear", "velocity": [0, 0, 0.1] } } ],
      "integrator": { "method": "explicit_euler", "dt": 0.0001 }
    })",
                         "every feature (test)");
    s.integrator.method = method;
    return s;
}

class GpuStorageBlocks : public GpuTest {};

TEST_F(GpuStorageBlocks, CountedBlocksAreTheActiveOnesAndTooFewIsRefusedByName) {
    const GpuInfo& info = GlContext::instance().info();
    int most = 0;
    std::string mostKernel;
    for (Method m : kMethods) {
        for (Kernel k : kernelsOf(m)) {
            const ShaderSource source =
                assembleKernel(kShaderDir, kernelFile(k), everyFeature(m), {});
            const int counted = storageBlockCount(source);
            const unsigned program = compileComputeProgram(source);
            GLint active = 0;
            glGetProgramInterfaceiv(program, GL_SHADER_STORAGE_BLOCK, GL_ACTIVE_RESOURCES, &active);
            glDeleteProgram(program);
            // The loader's count may only be larger than the driver's (a declared block the
            // compiler found unused): refusing on it is safe, never too late.
            EXPECT_GE(counted, active) << methodName(m) << " " << source.name;
            EXPECT_GE(counted, 1) << source.name;
            EXPECT_NO_THROW(checkStorageBlocks(source, info.maxComputeStorageBlocks))
                << source.name;
            if (counted > most) most = counted, mostKernel = source.name;
        }
    }
    // What GL guarantees is not enough for the largest kernel: a device with only 8 is told so.
    ASSERT_GT(most, 8) << mostKernel;
    const ShaderSource widest = [&] {
        for (Method m : kMethods)
            for (Kernel k : kernelsOf(m)) {
                ShaderSource s = assembleKernel(kShaderDir, kernelFile(k), everyFeature(m), {});
                if (s.name == mostKernel) return s;
            }
        return ShaderSource{};
    }();
    try {
        checkStorageBlocks(widest, 8);
        ADD_FAILURE() << mostKernel << " was accepted on a device of 8 storage blocks";
    } catch (const GpuUnavailable& e) {
        const std::string m = e.what();
        for (const std::string& word : {mostKernel, std::to_string(most) + " shader storage blocks",
                                        std::string("allows 8"), std::string("--backend cpu")})
            EXPECT_NE(m.find(word), std::string::npos) << m;
    }
}

}  // namespace
}  // namespace cloth::test
