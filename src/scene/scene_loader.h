// Reads and validates a scene file (DESIGN.md §4). Every key is checked for type and range,
// unknown keys are rejected, and an error names the file, the key path and the reason.
#pragma once

#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth {

// Loads `path`, applies each override "KEY.PATH=JSON" (the command line's --set) to the JSON
// document, then validates the result. Throws InputError.
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same, from text already in memory; `source` names it in messages.
Scene parseScene(const std::string& text, const std::string& source,
                 const std::vector<std::string>& overrides = {});

// Bytes of memory a cloth needs per vertex at the least (the explicit schemes' CPU arrays); the
// loader refuses a resolution whose need exceeds the machine's physical memory before anything
// is allocated. The CPU solver checks its integrator's own arrays (cpu/cpu_memory.h).
inline constexpr double kBytesPerVertex = 160;

}  // namespace cloth
