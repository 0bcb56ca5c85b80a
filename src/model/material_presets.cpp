#include "model/material_presets.h"

namespace cloth {
namespace {

// docs/physics.md "Presets" gives each number's source, its original unit and the conversion.
// Units: density kg/m², stretch and shear N/m (per unit width), bend N·m, air_damping 1/s. The
// air damping is the linearised drag of docs/physics.md, c = 0.15 kg/m²/s ÷ density. No preset
// damps its springs: spring_damping (s) is the scene's choice (docs/physics.md "Spring damping").
// clang-format off
const Material kPresets[] = {
    // preset       density  stretch  shear  bend      air_damping  spring_damping
    {"cotton",      0.150,   261,     105,   1.82e-5,  1.00,        0},
    {"silk",        0.052,   172,     14.3,  2.79e-6,  2.88,        0},
    {"denim",       0.324,   913,     53.4,  7.89e-5,  0.463,       0},
    {"wool",        0.235,   97,      32,    7.00e-6,  0.638,       0},
    {"polyester",   0.113,   172,     14.3,  1.71e-5,  1.33,        0},
    {"rubber",      0.475,   750,     250,   2.08e-5,  0.316,       0},
};
// clang-format on

}  // namespace

std::span<const Material> materialPresets() {
    return kPresets;
}

std::optional<Material> materialPreset(const std::string& name) {
    for (const Material& m : kPresets)
        if (m.preset == name) return m;
    return std::nullopt;
}

std::string materialPresetList() {
    std::string list;
    for (const Material& m : kPresets) list += (list.empty() ? "" : ", ") + m.preset;
    return list;
}

}  // namespace cloth
