// `--set KEY.PATH=JSON` (DESIGN.md §5): an edit of the scene's JSON document before validation,
// so an override is checked by exactly the same rules as the file.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace cloth {

// Applies "KEY.PATH=JSON" to `doc` (objects on the path are created; list entries are named as
// `colliders.1.radius` or `colliders[1].radius`). Returns the key path in the form validation
// messages use (`colliders[1].radius`). Throws InputError naming `source` and the key.
std::string applyOverride(nlohmann::json& doc, const std::string& assignment,
                          const std::string& source);

// The earlier assignments that `later` replaces (the same key in either spelling, or a key
// inside the value `later` sets), one notice line each for the app to print: the later wins,
// as a later argument does, but a value the user typed is not dropped without a word.
std::vector<std::string> replacedOverrides(const std::vector<std::string>& earlier,
                                           const std::string& later);

}  // namespace cloth
