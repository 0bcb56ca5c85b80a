// The material block (docs/physics.md "Materials"): a preset, overrides on top of it, the values
// --set edits, and a saved scene that loads back with the same material.
#include <gtest/gtest.h>

#include "model/errors.h"
#include "model/material_presets.h"
#include "scene/params.h"
#include "scene/scene_json.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth {
namespace {

constexpr const char* kDenim = R"({"cloth": {"resolution": [9, 5], "size": [1, 0.5]},
    "material": {"preset": "denim", "bend": 1e-4}, "integrator": {"dt": 1e-4}})";

TEST(MaterialLoader, APresetWithAnOverrideKeepsTheRestOfThePreset) {
    const Scene s = parseScene(kDenim, "denim.json");
    ASSERT_TRUE(s.material);
    const Material denim = *materialPreset("denim");
    EXPECT_EQ(s.material->preset, "denim");
    EXPECT_EQ(s.material->density, denim.density);
    EXPECT_EQ(s.material->stretch, denim.stretch);
    EXPECT_EQ(s.material->shear, denim.shear);
    EXPECT_EQ(s.material->airDamping, denim.airDamping);
    EXPECT_EQ(s.material->bend, 1e-4);
    // The per-vertex form's keys are not in force: the table hides them, shows the material's.
    EXPECT_FALSE(paramSpec("cloth.mass").get(s));
    EXPECT_FALSE(paramSpec("springs.structural").get(s));
    EXPECT_EQ(paramSpec("material.stretch").get(s), denim.stretch);
    // The grid models the material: its masses, no bend springs, the drag rate.
    EXPECT_DOUBLE_EQ(s.totalMass(), denim.density * 0.5);
    EXPECT_EQ(s.slotStiffness(8), 0);
    EXPECT_EQ(s.dampingRate(), denim.airDamping);
    EXPECT_EQ(s.bendingStiffness(), 1e-4);
    // No preset damps its springs.
    EXPECT_EQ(s.springDamping(), 0);
    EXPECT_FALSE(Features::of(s).springDamping);
}

TEST(MaterialLoader, WithoutAPresetTheValuesAreRequiredAndTheRestDefaultToOff) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [3, 3], "size": [1, 1]},
        "material": {"density": 0.2, "stretch": 800, "shear": 40}, "integrator": {"dt": 1e-4}})",
                               "custom.json");
    ASSERT_TRUE(s.material);
    EXPECT_EQ(s.material->preset, "");
    EXPECT_EQ(s.material->bend, 0);
    EXPECT_EQ(s.material->airDamping, 0);
    EXPECT_EQ(s.dampingRate(), 0);
    EXPECT_EQ(s.material->springDamping, 0);
}

TEST(MaterialLoader, SpringDampingIsReadSetAndSaved) {
    const Scene s = parseScene(R"({"cloth": {"resolution": [9, 5], "size": [1, 0.5]},
        "material": {"preset": "cotton", "spring_damping": 2e-5}, "integrator": {"dt": 1e-4}})",
                               "cotton.json");
    EXPECT_EQ(s.springDamping(), 2e-5);
    EXPECT_TRUE(Features::of(s).springDamping);
    EXPECT_EQ(paramSpec("material.spring_damping").get(s), 2e-5);
    EXPECT_EQ(parseScene(kDenim, "d.json", {"material.spring_damping=3e-4"}).springDamping(), 3e-4);
    const Scene back = parseScene(sceneToJson(s), "saved");
    EXPECT_EQ(back.material->springDamping, 2e-5);
    EXPECT_EQ(sceneToJson(back), sceneToJson(s));
    try {
        parseScene(kDenim, "d.json", {"material.spring_damping=-1e-5"});
        FAIL() << "a negative spring damping was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "material.spring_damping");
    }
}

TEST(MaterialLoader, SetEditsAMaterialKeyAndIsCheckedLikeTheFile) {
    EXPECT_EQ(parseScene(kDenim, "d.json", {"material.density=0.4"}).material->density, 0.4);
    EXPECT_EQ(parseScene(kDenim, "d.json", {"material.preset=\"silk\""}).material->density,
              materialPreset("silk")->density);
    try {
        parseScene(kDenim, "d.json", {"material.shear=-1"});
        FAIL() << "a negative shear stiffness was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "material.shear");
    }
}

TEST(MaterialLoader, ASavedMaterialSceneLoadsBackTheSame) {
    const Scene a = parseScene(kDenim, "denim.json");
    const Scene b = parseScene(sceneToJson(a), "saved");
    ASSERT_TRUE(b.material);
    EXPECT_EQ(b.material->preset, a.material->preset);
    EXPECT_EQ(b.material->density, a.material->density);
    EXPECT_EQ(b.material->stretch, a.material->stretch);
    EXPECT_EQ(b.material->shear, a.material->shear);
    EXPECT_EQ(b.material->bend, a.material->bend);
    EXPECT_EQ(b.material->airDamping, a.material->airDamping);
    EXPECT_EQ(b.material->springDamping, a.material->springDamping);
    EXPECT_EQ(sceneToJson(a), sceneToJson(b));
    // The per-vertex form's keys are not written: the file would be refused with both.
    EXPECT_EQ(sceneToJson(a).find("\"springs\""), std::string::npos);
    EXPECT_EQ(sceneToJson(a).find("\"mass\""), std::string::npos);
}

}  // namespace
}  // namespace cloth
