// A Scene written back as the JSON of DESIGN.md §4, every key explicit, so that loading it
// gives the same scene (the viewer's "save parameters").
#pragma once

#include <string>

#include "model/scene.h"

namespace cloth {

std::string sceneToJson(const Scene& scene);

}  // namespace cloth
