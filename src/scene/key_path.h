// Key paths as messages name them: `cloth.resolution`, `colliders[1].radius`.
#pragma once

#include <string>

namespace cloth {

inline std::string child(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
}

inline std::string element(const std::string& parent, size_t n) {
    return parent + "[" + std::to_string(n) + "]";
}

}  // namespace cloth
