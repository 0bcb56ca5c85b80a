// The malformed scenes of tests/data/bad_scenes and the key path each must be refused for,
// shared by the command-line tests and the loader's own tests.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cloth::test {

inline const std::filesystem::path kDataDir =
    std::filesystem::path(CLOTH_SOURCE_DIR) / "tests" / "data";
inline const std::filesystem::path kBadDir = kDataDir / "bad_scenes";
inline const std::filesystem::path kGoodScene = kDataDir / "good_scene.json";

struct BadScene {
    std::string file;               // name inside tests/data/bad_scenes
    std::vector<std::string> keys;  // the message names one of these; empty: no key applies
};

// gtest prints parameters in failure lines; the file name says it all.
void PrintTo(const BadScene& b, std::ostream* os);

std::string readFile(const std::filesystem::path& p);

// tests/data/bad_scenes/expected.json: every bad file with its key paths.
std::vector<BadScene> loadManifest();

}  // namespace cloth::test
