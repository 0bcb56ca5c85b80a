// The scalar parameters of a scene: key path, unit, valid range, default, the viewer's slider
// and meaning. One table drives the loader's range checks and defaults (and so `--set`, which
// edits the document the loader reads), `clothsim validate`'s parameter listing,
// docs/parameters.md and the viewer's sliders: a row added here appears in all of them.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "model/scene.h"

namespace cloth {

// Where the viewer's panel draws a row's slider; Hidden rows are not in the viewer.
enum class PanelSection { Hidden, TimeStep, Forces, Wind };
enum class SliderScale { Linear, Log };

struct SliderSpec {
    PanelSection section = PanelSection::Hidden;
    SliderScale scale = SliderScale::Linear;
    double min = 0, max = 0;  // inside the valid range; the slider clamps to it
    const char* label = "";   // ASCII: the panel's font has no "·"
    const char* format = "%.3g";
};

struct ParamSpec {
    const char* path;  // key path in the scene file; "colliders[].radius" for list entries
    const char* unit;
    double min, max;
    bool minExclusive;  // min < value rather than min ≤ value
    bool integer;
    double defaultValue;  // what the loader takes when the key is absent (and Scene{} holds)
    bool required;        // absent is an error (when the enclosing object is present)
    const char* description;
    SliderSpec slider = {};
    // The value in a Scene; get gives nullopt where the scene does not model it (no wind).
    // Both are null for list entries, which have no one value per scene.
    std::optional<double> (*get)(const Scene&) = nullptr;
    void (*set)(Scene&, double) = nullptr;
    bool maxExclusive = false;  // value < max rather than value ≤ max
};

std::span<const ParamSpec> paramTable();
const ParamSpec* findParam(const std::string& path);  // nullptr if the path has no entry
// The row of a path the code names; throws std::logic_error when the table lacks it.
const ParamSpec& paramSpec(const std::string& path);
// "" when value is inside the range, otherwise the reason, e.g. "must be > 0 s, got -1".
std::string checkRange(const ParamSpec& spec, double value);
// The table as docs/parameters.md holds it (`clothsim validate --params-markdown`).
std::string paramsMarkdown();

}  // namespace cloth
