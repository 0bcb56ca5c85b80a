// A scene file's text as a JSON document: syntax errors with line and column, and a value the
// parser cannot represent (1e999) named by its key path. Throws InputError.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace cloth {

nlohmann::json parseSceneText(const std::string& text, const std::string& source);

}  // namespace cloth
