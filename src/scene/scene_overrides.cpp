#include "scene/scene_overrides.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <vector>

#include "model/errors.h"
#include "scene/key_path.h"
#include "scene/scene_text.h"

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
            // An index into a list the scene does not have (colliders.1.radius on a scene without
            // colliders) would make an object keyed "1": say what is missing instead.
            if (node->is_null() && isIndex(part) && !path.empty())
                throw InputError(source, key,
                                 "--set: the scene has no " + path + ", so '" + part +
                                     "' is not an index of it (set the whole list: " + path +
                                     "=[...])");
            if (node->is_null()) *node = nlohmann::json::object();
            if (!node->is_object())
                throw InputError(
                    source, key,
                    "--set: " + (path.empty() ? "the scene" : path) + " is not an object");
            path += (path.empty() ? "" : ".") + part;
            node = &(*node)[part];
        }
    }
    // The same duplicate-key check as a file's (a value like {"bend": 1, "bend": 0}).
    try {
        parseSceneText(text, source);
    } catch (const InputError& e) {
        throw InputError(source, e.key().rfind('[', 0) == 0 ? path + e.key() : child(path, e.key()),
                         e.reason());
    }
    *node = std::move(value);
    return path;
}

std::vector<std::string> replacedOverrides(const std::vector<std::string>& earlier,
                                           const std::string& later) {
    std::vector<std::string> notices;
    const size_t eq = later.find('=');
    if (eq == std::string::npos || eq == 0) return notices;  // refused by applyOverride
    const std::vector<std::string> outer = splitKey(later.substr(0, eq));
    for (const std::string& e : earlier) {
        const size_t at = e.find('=');
        if (at == std::string::npos || at == 0) continue;
        const std::vector<std::string> inner = splitKey(e.substr(0, at));
        if (inner.size() >= outer.size() && std::equal(outer.begin(), outer.end(), inner.begin()))
            notices.push_back("--set " + later + " replaces the earlier --set " + e +
                              " (the later wins)");
    }
    return notices;
}

}  // namespace cloth
