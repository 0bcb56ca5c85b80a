// The shader variants written for the second compiler (scripts/check-shaders.sh) are the ones
// the backend builds: every kernel of every integrator, each name once, assembled with no GL.
#include "gpu/shader_variants.h"

#include <filesystem>
#include <set>

#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "scene/scene_loader.h"

namespace cloth::test {
namespace {

constexpr const char* kShaderDir = CLOTH_SOURCE_DIR "/shaders";

TEST(ShaderVariants, EveryKernelOfEveryIntegratorOnceByName) {
    const Scene scene = loadScene(CLOTH_SOURCE_DIR "/scenes/drape.json");
    const std::vector<ShaderVariant> variants = computeShaderVariants(kShaderDir, scene);
    std::set<std::string> names;
    for (const ShaderVariant& v : variants) {
        EXPECT_TRUE(names.insert(v.name).second) << v.name << " twice";
        EXPECT_EQ(v.source.text.rfind("#version 430\n", 0), 0u) << v.name;
        EXPECT_EQ(std::filesystem::path(v.name).extension(), ".comp") << v.name;
    }
    for (Method m : kMethods)
        for (Kernel k : kernelsOf(m)) {
            const std::string name = std::string(methodName(m)) + "." +
                                     std::filesystem::path(kernelFile(k)).stem().string() + ".comp";
            EXPECT_TRUE(names.count(name)) << name << " missing";
        }
    // The colliders compiled as dragged (the viewer) and the tiled forces pass are there too.
    EXPECT_TRUE(names.count("explicit_euler.dragged.tiled.forces.comp"));
    EXPECT_TRUE(names.count("symplectic_euler.many32.many_steps.comp"));
}

TEST(ShaderVariants, RenderShadersAreEveryStageFile) {
    std::set<std::string> names;
    for (const ShaderVariant& v : renderShaderVariants(kShaderDir)) names.insert(v.name);
    for (const char* file : {"cloth.vert", "cloth.frag", "lines.vert", "springs.vert", "mesh.frag"})
        EXPECT_TRUE(names.count(file)) << file;
}

}  // namespace
}  // namespace cloth::test
