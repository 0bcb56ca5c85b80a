#include "scene/scene_overrides.h"

#include <cctype>
#include <nlohmann/json.hpp>
#include <vector>

#include "model/errors.h"

namespace cloth {
namespace {

bool isIndex(const std::string& s) {
    if (s.empty() || s.size() > 9) return false;
    for (char c : s)
        if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    return true;
}

// "colliders[1].radius" and "colliders.1.radius" both give {"colliders", "1", "radius"}.
std::vector<std::string> splitKey(const std::string& key) {
    std::vector<std::string> parts(1);
    for (char c : key) {
        if (c == '.' || c == '[') {
            parts.emplace_back();
        } else if (c != ']') {
            parts.back() += c;
        }
    }
    return parts;
}

}  // namespace

std::string applyOverride(nlohmann::json& doc, const std::string& assignment,
                          const std::string& source) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw InputError(source, assignment,
                         "--set expects KEY.PATH=JSON, e.g. integrator.dt=0.002");
    const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
    nlohmann::json value;
    try {
        value = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error&) {
        throw InputError(source, key,
                         "--set value '" + text +
                             "' is not JSON (strings need quotes: "
                             "name='\"x\"')");
    } catch (const nlohmann::json::exception&) {
        throw InputError(source, key, "--set value '" + text + "' is not a finite number");
    }
    std::string path;
    nlohmann::json* node = &doc;
    const std::vector<std::string> parts = splitKey(key);
    for (size_t n = 0; n < parts.size(); ++n) {
        const std::string& part = parts[n];
        if (part.empty()) throw InputError(source, key, "--set key has an empty component");
        if (node->is_array()) {
            if (!isIndex(part) || std::stoul(part) >= node->size())
                throw InputError(source, key,
                                 "--set: '" + part + "' is not an index of " + path + " (it has " +
                                     std::to_string(node->size()) + " entries)");
            path += "[" + part + "]";
            node = &(*node)[std::stoul(part)];
        } else {
            if (node->is_null()) *node = nlohmann::json::object();
            if (!node->is_object())
                throw InputError(
                    source, key,
                    "--set: " + (path.empty() ? "the scene" : path) + " is not an object");
            path += (path.empty() ? "" : ".") + part;
            node = &(*node)[part];
        }
    }
    *node = std::move(value);
    return path;
}

}  // namespace cloth
