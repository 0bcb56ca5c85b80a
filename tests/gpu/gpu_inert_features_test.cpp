// bench speed --features all on the GPU: the inert scene compiles HAS_WIND, the colliders and
// every spring family into the kernels (its own shader variant) and moves as the declared scene.
#include "bench/bench_features.h"
#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

class GpuInertFeatures : public GpuTest {};

TEST_F(GpuInertFeatures, MovesAsTheDeclaredScene) {
    const Scene s = loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json",
                              {"cloth.resolution=[19,13]"});  // not multiples of a work group
    const Scene inert = app::withInertFeatures(s);
    ASSERT_FALSE(Features::of(inert) == Features::of(s));
    const SimState a = runGpu(s, 100), b = runGpu(inert, 100);
    EXPECT_LE(maxDifferenceOverExtent(a, b, s.grid().extent()), 1e-6);
}

}  // namespace
}  // namespace cloth::test
