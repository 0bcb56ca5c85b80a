// Fabrics a scene can name as "material": {"preset": "cotton"}, with the published measurements
// they come from in docs/physics.md ("Presets").
#pragma once

#include <optional>
#include <span>
#include <string>

#include "model/scene.h"

namespace cloth {

std::span<const Material> materialPresets();
std::optional<Material> materialPreset(const std::string& name);  // nullopt: no such preset
std::string materialPresetList();                                 // "cotton, silk, ..."

}  // namespace cloth
