// bench speed --features: the inert scene compiles every feature in (Features::of counts them
// all) and moves as the declared scene does, so timing it against the declared one is fair.
#include "bench/bench_features.h"

#include <gtest/gtest.h>

#include "cpu/cpu_backend.h"
#include "model/errors.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

// The speed benchmark's default scene: the seed's per-vertex hanging cloth.
Scene hanging(int n) {
    return loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json",
                     {"cloth.resolution=[" + std::to_string(n) + "," + std::to_string(n) + "]"});
}

TEST(BenchFeatures, InertSceneDeclaresEveryFeature) {
    const Scene s = hanging(8);
    const Features declared = Features::of(s);
    EXPECT_FALSE(declared.wind);
    EXPECT_EQ(declared.planes + declared.spheres, 0);
    const Features all = Features::of(app::withInertFeatures(s));
    EXPECT_TRUE(all.structural && all.shear && all.bend && all.wind);
    EXPECT_EQ(all.planes, 1);
    EXPECT_EQ(all.spheres, 1);
    Scene bare = s;  // absent families and a declared-but-zero wind become inert ones
    bare.springs.shear = bare.springs.bend = 0;
    bare.wind = Wind{glm::dvec3(0, 0, 1), 0};
    const Scene inert = app::withInertFeatures(bare);
    EXPECT_EQ(inert.springs.shear, app::kInertStrength);
    EXPECT_EQ(inert.springs.structural, s.springs.structural);
    EXPECT_TRUE(Features::of(inert).wind && Features::of(inert).bend);
}

// CPU double after 100 steps: within 1e-12 of the extent of the declared scene's trajectory.
// Float: the 1e-30 N forces vanish below its rounding too, so within a few float ulps.
TEST(BenchFeatures, InertSceneMovesAsTheDeclaredOne) {
    const Scene s = hanging(16);
    const double extent = s.grid().extent();
    for (const auto& [precision, tolerance] :
         {std::pair{Precision::Double, 1e-12}, std::pair{Precision::Float, 1e-6}}) {
        auto declared = makeCpuSolver(s, {precision, 1});
        auto all = makeCpuSolver(app::withInertFeatures(s), {precision, 1});
        ASSERT_FALSE(declared->step(100).unstable);
        ASSERT_FALSE(all->step(100).unstable);
        const SimState a = declared->read(), b = all->read();
        double worst = 0;
        for (std::size_t k = 0; k < a.positions.size(); ++k)
            worst = std::max(worst, glm::length(a.positions[k] - b.positions[k]));
        EXPECT_LE(worst, tolerance * extent) << precisionName(precision);
        EXPECT_GT(glm::length(a.positions[255] - s.grid().restPosition(15, 15)), 0);  // it moved
    }
}

TEST(BenchFeatures, OptionValues) {
    EXPECT_EQ(app::parseFeatureSet("--features", "declared"), app::FeatureSet::Declared);
    EXPECT_EQ(app::parseFeatureSet("--features", "all"), app::FeatureSet::All);
    EXPECT_EQ(app::parseFeatureSet("--features", "both"), app::FeatureSet::Both);
    try {
        app::parseFeatureSet("--features", "some");
        FAIL() << "accepted 'some'";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "--features");
    }
}

}  // namespace
}  // namespace cloth
