#include "scene/params.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace cloth {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// DESIGN.md §4. Ranges are physical (mass > 0, Δt > 0), or guard against sizes no machine has.
constexpr ParamSpec kParams[] = {
    {"cloth.mass", "kg", 0, kInf, true, false, "mass of each vertex"},
    {"springs.structural", "N/m", 0, kInf, false, false,
     "stiffness of the (±1,0), (0,±1) springs; 0 = not modelled"},
    {"springs.shear", "N/m", 0, kInf, false, false,
     "stiffness of the (±1,±1) springs; 0 = not modelled"},
    {"springs.bend", "N/m", 0, kInf, false, false,
     "stiffness of the (±2,0), (0,±2) springs; 0 = not modelled"},
    {"damping", "N·s/m", 0, kInf, false, false, "viscous damping μ, F = −μv"},
    {"integrator.dt", "s", 0, 10, true, false, "time step Δt"},
    {"integrator.substeps", "", 1, 100000, false, true, "steps per displayed frame (viewer)"},
    {"integrator.tolerance", "", 0, 1, true, false,
     "implicit_euler: CG stops at |residual| <= tolerance·|right-hand side|"},
    {"integrator.max_iterations", "", 1, 100000, false, true,
     "implicit_euler: CG iteration cap per step (a miss is reported)"},
    {"wind.strength", "N", -kInf, kInf, false, false, "K_w in F = K_w ⟨n, û_w⟩ n"},
    {"max_speed", "m/s", 0, kInf, true, false, "a faster vertex means the run is unstable"},
    {"duration", "s", 0, 1e9, true, false, "simulated time `run` covers without --steps"},
    {"colliders[].radius", "m", 0, kInf, true, false, "sphere radius"},
};

}  // namespace

std::span<const ParamSpec> paramTable() {
    return kParams;
}

const ParamSpec* findParam(const std::string& path) {
    for (const ParamSpec& p : kParams)
        if (path == p.path) return &p;
    return nullptr;
}

std::string checkRange(const ParamSpec& spec, double value) {
    char buf[160];
    const char* unit = spec.unit[0] ? spec.unit : "";
    if (!std::isfinite(value)) return "must be a finite number";
    if (spec.integer && value != std::floor(value)) {
        std::snprintf(buf, sizeof buf, "must be an integer, got %.17g", value);
        return buf;
    }
    const bool below = spec.minExclusive ? !(value > spec.min) : !(value >= spec.min);
    if (below) {
        std::snprintf(buf, sizeof buf, "must be %s %g%s%s, got %.17g",
                      spec.minExclusive ? ">" : ">=", spec.min, unit[0] ? " " : "", unit, value);
        return buf;
    }
    if (value > spec.max) {
        std::snprintf(buf, sizeof buf, "must be <= %g%s%s, got %.17g", spec.max, unit[0] ? " " : "",
                      unit, value);
        return buf;
    }
    return "";
}

}  // namespace cloth
