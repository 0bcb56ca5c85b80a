// scene/params.cpp's table against its consumers: the loader takes each row's default when the
// key is absent and refuses a value just outside its range naming the key (through `--set`,
// which edits the document the loader checks), Scene{} holds the same defaults, and
// docs/parameters.md is the table's current Markdown.
#include "scene/params.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "model/errors.h"
#include "scene/scene_loader.h"

namespace cloth {
namespace {

// Every key of the table, each at a value other than its default.
const nlohmann::json kFull = nlohmann::json::parse(R"({
  "cloth": {"resolution": [4, 3], "size": [1, 1], "mass": 0.5},
  "springs": {"structural": 10, "shear": 5, "bend": 1},
  "damping": 0.1,
  "integrator": {"method": "vbd", "dt": 0.002, "substeps": 3, "tolerance": 1e-4,
                 "max_iterations": 50, "iterations": 20, "chebyshev_rho": 0.5,
                 "translation_sweeps": 2, "translation_levels": 3, "translation_level_passes": 2,
                 "translation_block_width": 8,
                 "max_step_strain": 0.2},
  "wind": {"direction": [1, 0, 0], "strength": 0.5},
  "colliders": [{"type": "sphere", "center": [0, -2, 0], "radius": 0.3}],
  "self_collision": {"thickness": 0.01, "friction": 0.2},
  "max_speed": 100,
  "max_strain": 2.5,
  "duration": 2
})");

// The material rows, which a scene gives instead of the per-vertex form's (cloth.mass, springs,
// damping), each at a value other than its default.
const nlohmann::json kFullMaterial = nlohmann::json::parse(R"({
  "cloth": {"resolution": [4, 3], "size": [1, 1]},
  "material": {"density": 0.2, "stretch": 900, "shear": 40, "bend": 1e-5, "air_damping": 0.5,
               "spring_damping": 1e-4},
  "integrator": {"dt": 0.002}
})");

// kFull's method is vbd; implicit_euler's rows are read under implicit_euler (a row's get() is
// empty where the scene's method does not use its key).
nlohmann::json fullFor(const ParamSpec& p) {
    const std::string path = p.path;
    if (path.rfind("material.", 0) == 0) return kFullMaterial;
    nlohmann::json doc = kFull;
    if (path == "integrator.tolerance" || path == "integrator.max_iterations")
        doc["integrator"]["method"] = "implicit_euler";
    return doc;
}

// "colliders[].radius" names the first entry: "colliders[0].radius".
std::string keyOf(const ParamSpec& p) {
    std::string key = p.path;
    if (const size_t at = key.find("[]"); at != std::string::npos) key.replace(at, 2, "[0]");
    return key;
}

// The JSON pointer of a key path: "colliders[0].radius" → "/colliders/0/radius".
nlohmann::json::json_pointer pointerOf(const std::string& key) {
    std::string ptr = "/";
    for (char c : key) {
        if (c == '.' || c == '[') {
            ptr += '/';
        } else if (c != ']') {
            ptr += c;
        }
    }
    return nlohmann::json::json_pointer(ptr);
}

Scene load(const nlohmann::json& doc, const std::vector<std::string>& sets = {}) {
    return parseScene(doc.dump(), "params.json", sets);
}

TEST(ParamTable, EveryRowIsInTheTestScene) {
    for (const ParamSpec& p : paramTable())
        EXPECT_TRUE(fullFor(p).contains(pointerOf(keyOf(p))))
            << "add " << p.path << " to kFull (or kFullMaterial)";
}

TEST(ParamTable, AnOmittedKeyLoadsAsTheRowsDefault) {
    for (const ParamSpec& p : paramTable()) {
        SCOPED_TRACE(p.path);
        const Scene full = load(fullFor(p));
        nlohmann::json doc = fullFor(p);
        const nlohmann::json::json_pointer ptr = pointerOf(keyOf(p));
        doc[ptr.parent_pointer()].erase(ptr.back());
        if (p.required) {
            try {
                load(doc);
                ADD_FAILURE() << "loaded without a required key";
            } catch (const InputError& e) {
                EXPECT_EQ(e.key(), keyOf(p));
            }
            continue;
        }
        ASSERT_TRUE(p.get) << "a scene-level row needs its accessor";
        EXPECT_NE(*p.get(full), p.defaultValue) << "kFull should not hold the default";
        EXPECT_EQ(*p.get(load(doc)), p.defaultValue);
    }
}

TEST(ParamTable, DefaultsAreTheSceneStructs) {
    const Scene plain;
    for (const ParamSpec& p : paramTable()) {
        if (p.get && p.get(plain)) {
            EXPECT_EQ(*p.get(plain), p.defaultValue) << p.path;
        }
    }
}

void expectRefused(const ParamSpec& p, double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    const std::string set = keyOf(p) + "=" + text;
    try {
        load(fullFor(p), {set});
        ADD_FAILURE() << "--set " << set << " was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), keyOf(p)) << set;
        EXPECT_NE(e.reason().find("--set " + keyOf(p)), std::string::npos) << e.reason();
    }
}

TEST(ParamTable, AValueJustOutsideTheRangeIsRefusedNamingTheKey) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    for (const ParamSpec& p : paramTable()) {
        SCOPED_TRACE(p.path);
        if (std::isfinite(p.min)) expectRefused(p, p.minExclusive ? p.min : p.min - 1e-9);
        if (std::isfinite(p.max))
            expectRefused(p, p.maxExclusive ? p.max : std::nextafter(p.max, kInf));
        if (p.integer) expectRefused(p, p.min + 0.5);
    }
}

TEST(ParamTable, TheSliderRangeLiesInsideTheValidRange) {
    for (const ParamSpec& p : paramTable()) {
        if (p.slider.section == PanelSection::Hidden) continue;
        EXPECT_TRUE(p.get && p.set) << p.path << ": a slider needs the row's accessors";
        EXPECT_LT(p.slider.min, p.slider.max) << p.path;
        EXPECT_TRUE(p.slider.min >= p.min && p.slider.max <= p.max) << p.path;
    }
}

// Regenerate with: build/clothsim validate --params-markdown > docs/parameters.md
TEST(ParamTable, DocsParametersMdIsCurrent) {
    std::ifstream in(CLOTH_SOURCE_DIR "/docs/parameters.md", std::ios::binary);
    std::ostringstream doc;
    doc << in.rdbuf();
    EXPECT_EQ(doc.str(), paramsMarkdown())
        << "docs/parameters.md is stale: build/clothsim validate --params-markdown > "
           "docs/parameters.md";
}

}  // namespace
}  // namespace cloth
