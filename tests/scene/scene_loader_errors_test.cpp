// The scene loader refuses malformed input with an InputError naming the file and key path
// (DESIGN.md §4); the command-line side of the same cases is in tests/app/bad_input_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>
#include <vector>

#include "model/errors.h"
#include "scene/scene_loader.h"
#include "support/bad_scenes.h"

namespace cloth {
namespace {

namespace fs = std::filesystem;
using test::BadScene;
using test::kBadDir;
using test::kGoodScene;
using test::loadManifest;
using test::readFile;

// ---- the loader itself: InputError with the key path --------------------------------------

std::string goodText() {
    return readFile(kGoodScene);
}

// The good scene with the value at `pointer` (JSON pointer) replaced by `value`.
std::string with(const std::string& pointer, const nlohmann::json& value) {
    auto j = nlohmann::json::parse(goodText());
    j[nlohmann::json::json_pointer(pointer)] = value;
    return j.dump();
}

// The InputError parseScene throws, failing the test if it throws nothing or something else.
InputError parseError(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
        parseScene(text, "mem.json", overrides);
    } catch (const InputError& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw " << typeid(e).name() << " not InputError: " << e.what();
        return InputError("", "", "");
    }
    ADD_FAILURE() << "accepted:\n" << text.substr(0, 400);
    return InputError("", "", "");
}

TEST(ParseScene, GoodSceneLoadsWithResolvedPinsAndUnitAxes) {
    const Scene s = parseScene(goodText(), "mem.json");
    EXPECT_EQ(s.cloth.nu, 4);
    EXPECT_EQ(s.cloth.nv, 3);
    ASSERT_EQ(s.pins.size(), 2u);
    EXPECT_EQ(s.pins[1].i, 3);  // -1 counts from the end
    EXPECT_EQ(s.pins[1].j, 0);
    EXPECT_DOUBLE_EQ(s.integrator.dt, 0.001);
    EXPECT_EQ(s.colliders.size(), 2u);
}

TEST(ParseScene, ThrowsInputErrorWithKeyPath) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {with("/integrator/dt", -1), "integrator.dt"},
        {with("/integrator/dt", 0), "integrator.dt"},
        {with("/integrator/dt", "NaN"), "integrator.dt"},
        {with("/cloth/resolution", {1, 1}), "cloth.resolution"},
        {with("/cloth/resolution", {100000, 100000}), "cloth.resolution"},
        {with("/cloth/resolution", {2147483647, 2}), "cloth.resolution"},
        {with("/cloth/mass", -1), "cloth.mass"},
        {with("/springs/bnd", 3), "springs.bnd"},
        {with("/colliders/1/radius", 0), "colliders[1].radius"},
        {with("/colliders/1/type", "cylinder"), "colliders[1].type"},
        // In range, but the contact test squares them.
        {with("/colliders/1/radius", 1e308), "colliders[1].radius"},
        {with("/colliders/1/thickness", 1e300), "colliders[1].thickness"},
        {with("/pins/1", {4, 0}), "pins[1]"},
        {with("/pins/1", {-5, 0}), "pins[1]"},
        {with("/wind/direction", {0, 0, 0}), "wind.direction"},
        {with("/colour", "red"), "colour"},
        // The name starts the --frames files' names: no path out of the folder, no new lines
        // in the OBJ's object line.
        {with("/name", "../escaped"), "name"},
        {with("/name", "a\\b"), "name"},
        {with("/name", "two\nlines"), "name"},
        {with("/name", ""), "name"},
    };
    for (const auto& [text, key] : cases) {
        SCOPED_TRACE(key);
        const InputError e = parseError(text);
        EXPECT_EQ(e.key(), key) << e.what();
        EXPECT_EQ(e.file(), "mem.json") << e.what();
        EXPECT_FALSE(e.reason().empty());
    }
}

TEST(ParseScene, NotJsonNamesSourceWithoutKey) {
    for (const std::string text : {"", "{", "[1, 2]", "{\"dt\": 1e999}", "null"}) {
        SCOPED_TRACE(text);
        const InputError e = parseError(text);
        EXPECT_EQ(e.file(), "mem.json") << e.what();
        EXPECT_FALSE(e.reason().empty());
    }
}

TEST(ParseScene, BadOverridesThrowInputErrorWithKeyPath) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"integrator.dt=-1", "integrator.dt"},
        {"integrator.dt=notjson", "integrator.dt"},
        {"springs.bnd=3", "springs.bnd"},
    };
    for (const auto& [set, key] : cases) {
        SCOPED_TRACE(set);
        EXPECT_EQ(parseError(goodText(), {set}).key(), key);
    }
    parseError(goodText(), {"nokey"});
}

// ---- duplicate keys: the parser would keep the last silently ----------------------------

TEST(ParseScene, DuplicateKeyNamesKeyPathAndBothLines) {
    std::string text = goodText();
    const std::string bend = "    \"bend\": 10.0\n";
    ASSERT_NE(text.find(bend), std::string::npos);
    text.replace(text.find(bend), bend.size(), "    \"bend\": 10.0,\n    \"bend\": 0\n");
    const InputError e = parseError(text);
    EXPECT_EQ(e.key(), "springs.bend") << e.what();
    EXPECT_NE(e.reason().find("32"), std::string::npos) << e.what();  // the first "bend"
    EXPECT_NE(e.reason().find("33"), std::string::npos) << e.what();  // the second
}

TEST(ParseScene, DuplicateKeyInsideListsAndOverridesNamesItsPath) {
    EXPECT_EQ(parseError(R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
        "integrator": {"dt": 0.001},
        "colliders": [{"type": "plane"}, {"type": "sphere", "radius": 1, "radius": 2}]})")
                  .key(),
              "colliders[1].radius");
    EXPECT_EQ(parseError(goodText(), {R"(springs={"bend": 1, "bend": 0})"}).key(), "springs.bend");
    // The same key in different objects is no duplicate.
    EXPECT_NO_THROW(parseScene(R"({"cloth": {"resolution": [2, 2], "size": [1, 1]},
        "integrator": {"dt": 0.001},
        "colliders": [{"type": "sphere", "center": [0, 0, 0], "radius": 1},
                      {"type": "sphere", "center": [0, 0, 0], "radius": 2}]})",
                               "mem.json"));
}

// A document nested past 64 arrays and objects is refused where it goes past, naming the path
// so far, in time linear in the text: a million levels (2 MB) once took 77 s and gave a 3 MB
// message. 64 levels still parse (to the loader's own complaint about the key).
TEST(ParseScene, NestingPastSixtyFourLevelsIsRefusedWithoutQuadraticWork) {
    const int depth = 1000000;
    const std::string deep =
        "{\"cloth\": " + std::string(depth, '[') + "1e999" + std::string(depth, ']') + "}";
    const auto start = std::chrono::steady_clock::now();
    const InputError e = parseError(deep);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_NE(e.reason().find("nested deeper than 64"), std::string::npos) << e.reason();
    EXPECT_EQ(e.key().rfind("cloth[0]", 0), 0u) << e.key();
    EXPECT_LT(std::string(e.what()).size(), 1000u);
    EXPECT_LT(seconds, 2.0);
    const InputError shallow =
        parseError("{\"cloth\": " + std::string(63, '[') + "1" + std::string(63, ']') + "}");
    EXPECT_EQ(shallow.reason().find("nested"), std::string::npos) << shallow.reason();
}

// ---- derived quantities that overflow although every key is in range --------------------

TEST(ParseScene, OverflowingDerivedQuantityNamesTheKeyThatCausesIt) {
    struct Case {
        std::string pointer;
        nlohmann::json value;
        std::string key;
    };
    const std::vector<Case> cases = {
        {"/springs/structural", 1e308, "springs.structural"},
        {"/springs/shear", 1e200, "springs.shear"},
        {"/cloth/size", {1e308, 1e308}, "cloth.size"},
        {"/cloth/size", {1e200, 0.5}, "cloth.size"},
        {"/cloth/size", {5e-324, 0.5}, "cloth.size"},
        {"/cloth/origin", {1e200, 0, 0}, "cloth.origin"},
        {"/cloth/mass", 1e-320, "cloth.mass"},
        {"/cloth/mass", 1e308, "cloth.mass"},
        {"/gravity", {0, -1e308, 0}, "gravity"},
        {"/damping", 1e308, "damping"},
        {"/max_speed", 1e308, "max_speed"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.pointer + " = " + c.value.dump());
        const InputError e = parseError(with(c.pointer, c.value));
        EXPECT_EQ(e.key(), c.key) << e.what();
        EXPECT_NE(e.reason().find("flow"), std::string::npos) << e.what();  // over- or underflow
    }
    // Origin and size each fine alone, their sum is not.
    auto both = nlohmann::json::parse(with("/cloth/origin", {1e154, 0, 0}));
    both["cloth"]["size"] = {1e154, 0.5};
    EXPECT_EQ(parseError(both.dump()).key(), "cloth.origin");
    // The wind's acceleration K_w/m, with a light cloth.
    auto wind = nlohmann::json::parse(with("/wind/strength", -1e308));
    wind["cloth"]["mass"] = 1e-3;
    EXPECT_EQ(parseError(wind.dump()).key(), "wind.strength");
    // Large but representable values still load.
    EXPECT_NO_THROW(parseScene(with("/springs/structural", 1e12), "mem.json"));
    EXPECT_NO_THROW(parseScene(with("/cloth/size", {1e6, 1e6}), "mem.json"));
    EXPECT_NO_THROW(parseScene(with("/cloth/mass", 1e-12), "mem.json"));
}

TEST(LoadScene, MissingFileAndDirectoryThrowInputError) {
    for (const fs::path& p : {kBadDir / "no_such_scene.json", kBadDir}) {
        SCOPED_TRACE(p.string());
        try {
            loadScene(p.string());
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), p.string()) << e.what();
        }
    }
}

TEST(LoadScene, EveryBadSceneThrowsInputError) {
    for (const BadScene& b : loadManifest()) {
        SCOPED_TRACE(b.file);
        const std::string path = (kBadDir / b.file).string();
        try {
            loadScene(path);
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), path) << e.what();
            if (!b.keys.empty()) {
                EXPECT_TRUE(std::any_of(b.keys.begin(), b.keys.end(), [&](const std::string& k) {
                    return e.key().rfind(k, 0) == 0;  // "cloth.resolution[0]" names it too
                })) << e.what();
            }
        } catch (const std::exception& e) {
            ADD_FAILURE() << "threw " << typeid(e).name() << " not InputError: " << e.what();
        }
    }
}

}  // namespace
}  // namespace cloth
