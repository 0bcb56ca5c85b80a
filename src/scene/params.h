// The scalar parameters of a scene: name, unit, range and meaning. One table drives the loader's
// range checks, `clothsim validate`, and the viewer's sliders.
#pragma once

#include <span>
#include <string>

namespace cloth {

struct ParamSpec {
    const char* path;  // key path in the scene file; "colliders[].radius" for list entries
    const char* unit;
    double min, max;
    bool minExclusive;  // min < value rather than min ≤ value
    bool integer;
    const char* description;
};

std::span<const ParamSpec> paramTable();
const ParamSpec* findParam(const std::string& path);  // nullptr if the path has no entry
// "" when value is inside the range, otherwise the reason, e.g. "must be > 0 s, got -1".
std::string checkRange(const ParamSpec& spec, double value);

}  // namespace cloth
