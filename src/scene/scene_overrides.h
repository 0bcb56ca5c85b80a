// `--set KEY.PATH=JSON` (DESIGN.md §5): an edit of the scene's JSON document before validation,
// so an override is checked by exactly the same rules as the file.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

namespace cloth {

// Applies "KEY.PATH=JSON" to `doc` (objects on the path are created; list entries are named as
// `colliders.1.radius` or `colliders[1].radius`). Returns the key path in the form validation
// messages use (`colliders[1].radius`). Throws InputError naming `source` and the key.
std::string applyOverride(nlohmann::json& doc, const std::string& assignment,
                          const std::string& source);

}  // namespace cloth
