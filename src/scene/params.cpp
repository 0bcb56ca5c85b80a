#include "scene/params.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace cloth {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr SliderSpec kHidden{};

// DESIGN.md §4. Ranges are physical (mass > 0, Δt > 0), or guard against sizes no machine has.
// Defaults are Scene{}'s (model/scene.h); tests/scene/params_test.cpp holds the two together.
// Slider ranges are what the panel offers, a working span inside the valid range.
// One row a parameter, kept in columns to read as a table.
// clang-format off
constexpr ParamSpec kParams[] = {
    {"cloth.mass", "kg", 0, kInf, true, false, 1, false, "mass of each vertex",
     {PanelSection::Forces, SliderScale::Log, 1e-5, 100, "mass [kg]"},
     [](const Scene& s) { return s.material ? std::nullopt : std::optional(s.cloth.mass); },
     [](Scene& s, double v) { s.cloth.mass = v; }},
    {"springs.structural", "N/m", 0, kInf, false, false, 0, false,
     "stiffness of the (±1,0), (0,±1) springs; 0 = not modelled",
     {PanelSection::Forces, SliderScale::Log, 0, 1e5, "structural [N/m]"},
     [](const Scene& s) { return s.material ? std::nullopt : std::optional(s.springs.structural); },
     [](Scene& s, double v) { s.springs.structural = v; }},
    {"springs.shear", "N/m", 0, kInf, false, false, 0, false,
     "stiffness of the (±1,±1) springs; 0 = not modelled",
     {PanelSection::Forces, SliderScale::Log, 0, 1e5, "shear [N/m]"},
     [](const Scene& s) { return s.material ? std::nullopt : std::optional(s.springs.shear); },
     [](Scene& s, double v) { s.springs.shear = v; }},
    {"springs.bend", "N/m", 0, kInf, false, false, 0, false,
     "stiffness of the (±2,0), (0,±2) springs; 0 = not modelled",
     {PanelSection::Forces, SliderScale::Log, 0, 1e5, "bend [N/m]"},
     [](const Scene& s) { return s.material ? std::nullopt : std::optional(s.springs.bend); },
     [](Scene& s, double v) { s.springs.bend = v; }},
    {"damping", "N·s/m", 0, kInf, false, false, 0, false, "viscous damping μ, F = −μv",
     {PanelSection::Forces, SliderScale::Log, 0, 100, "damping [N s/m]"},
     [](const Scene& s) { return s.material ? std::nullopt : std::optional(s.damping); },
     [](Scene& s, double v) { s.damping = v; }},
    // A material (docs/physics.md "Materials"): the SI alternative to the four rows above.
    {"material.density", "kg/m²", 0, kInf, true, false, 0, true,
     "areal density ρ (required unless the preset gives it)",
     {PanelSection::Forces, SliderScale::Log, 0.01, 3, "density [kg/m2]"},
     [](const Scene& s) { return s.material ? std::optional(s.material->density) : std::nullopt; },
     [](Scene& s, double v) { if (s.material) s.material->density = v; }},
    {"material.stretch", "N/m", 0, kInf, true, false, 0, true,
     "membrane tensile stiffness Y: force per width per unit strain (required unless the preset "
     "gives it)",
     {PanelSection::Forces, SliderScale::Log, 10, 1e6, "stretch [N/m]"},
     [](const Scene& s) { return s.material ? std::optional(s.material->stretch) : std::nullopt; },
     [](Scene& s, double v) { if (s.material) s.material->stretch = v; }},
    {"material.shear", "N/m", 0, kInf, true, false, 0, true,
     "membrane shear stiffness G (required unless the preset gives it)",
     {PanelSection::Forces, SliderScale::Log, 1, 1e5, "shear [N/m]"},
     [](const Scene& s) { return s.material ? std::optional(s.material->shear) : std::nullopt; },
     [](Scene& s, double v) { if (s.material) s.material->shear = v; }},
    {"material.bend", "N·m", 0, kInf, false, false, 0, false,
     "bending stiffness B: moment per width per unit curvature",
     {PanelSection::Forces, SliderScale::Log, 1e-8, 1e-2, "bend [N m]"},
     [](const Scene& s) { return s.material ? std::optional(s.material->bend) : std::nullopt; },
     [](Scene& s, double v) { if (s.material) s.material->bend = v; }},
    {"material.air_damping", "1/s", 0, kInf, false, false, 0, false,
     "drag per unit mass c: F = −c·m·v on each vertex",
     {PanelSection::Forces, SliderScale::Log, 0, 10, "air damping [1/s]"},
     [](const Scene& s) {
         return s.material ? std::optional(s.material->airDamping) : std::nullopt;
     },
     [](Scene& s, double v) { if (s.material) s.material->airDamping = v; }},
    {"material.spring_damping", "s", 0, kInf, false, false, 0, false,
     "damping along each spring β, in units of its stiffness: F = β·K·((v_q − v_k)·d̂)·d̂",
     {PanelSection::Forces, SliderScale::Log, 0, 1e-2, "spring damping [s]"},
     [](const Scene& s) {
         return s.material ? std::optional(s.material->springDamping) : std::nullopt;
     },
     [](Scene& s, double v) { if (s.material) s.material->springDamping = v; }},
    {"integrator.dt", "s", 0, 10, true, false, 1e-3, true, "time step Δt",
     {PanelSection::TimeStep, SliderScale::Log, 1e-6, 1e-1, "dt [s]", "%.3e"},
     [](const Scene& s) -> std::optional<double> { return s.integrator.dt; },
     [](Scene& s, double v) { s.integrator.dt = v; }},
    {"integrator.substeps", "", 1, 100000, false, true, 1, false,
     "steps per displayed frame (viewer)",
     {PanelSection::TimeStep, SliderScale::Log, 1, 2000, "substeps", "%d"},
     [](const Scene& s) -> std::optional<double> { return s.integrator.substeps; },
     [](Scene& s, double v) { s.integrator.substeps = int(std::lround(v)); }},
    {"integrator.tolerance", "", 0, 1, true, false, 1e-5, false,
     "implicit_euler: CG stops at |residual| <= tolerance·|right-hand side|", kHidden,
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::ImplicitEuler
                    ? std::optional<double>(s.integrator.tolerance) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.tolerance = v; }, true},
    {"integrator.max_iterations", "", 1, 100000, false, true, 200, false,
     "implicit_euler: CG iteration cap per step (a miss is reported)", kHidden,
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::ImplicitEuler
                    ? std::optional<double>(s.integrator.maxIterations) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.maxIterations = int(std::lround(v)); }},
    {"integrator.iterations", "", 1, 100000, false, true, 10, false,
     "vbd: Gauss–Seidel sweeps over the 5 colours per step",
     {PanelSection::TimeStep, SliderScale::Log, 1, 200, "vbd iterations", "%d"},
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd ? std::optional<double>(s.integrator.iterations)
                                                   : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.iterations = int(std::lround(v)); }},
    {"integrator.chebyshev_rho", "", 0, 0.999, false, false, 0, false,
     "vbd: spectral radius estimate ρ of the Chebyshev acceleration; 0 = none", kHidden,
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd ? std::optional<double>(s.integrator.chebyshevRho)
                                                   : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.chebyshevRho = v; }},
    {"integrator.translation_sweeps", "", 0, 100000, false, true, 1, false,
     "vbd: after each of the first N sweeps of a step, the Newton step on the rigid translation "
     "of the free vertices; 0 = none",
     {PanelSection::TimeStep, SliderScale::Linear, 0, 20, "vbd translation sweeps", "%d"},
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd
                    ? std::optional<double>(s.integrator.translationSweeps) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.translationSweeps = int(std::lround(v)); }},
    {"integrator.translation_levels", "", 0, 16, false, true, 4, false,
     "vbd: before the first sweep of a step, the same Newton step on the translation of each "
     "block of the sheet cut into 2 × 2, 4 × 4, … 2^N × 2^N parts (more where blocks would be "
     "wider than translation_block_width); 0 = none",
     {PanelSection::TimeStep, SliderScale::Linear, 0, 8, "vbd translation levels", "%d"},
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd
                    ? std::optional<double>(s.integrator.translationLevels) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.translationLevels = int(std::lround(v)); }},
    {"integrator.translation_level_passes", "", 1, 100000, false, true, 1, false,
     "vbd: how many times a step the translation levels run: before the first sweep and again "
     "spread evenly over the sweeps (at most one before each)",
     {PanelSection::TimeStep, SliderScale::Linear, 1, 5, "vbd level passes", "%d"},
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd
                    ? std::optional<double>(s.integrator.translationLevelPasses) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.translationLevelPasses = int(std::lround(v)); }},
    {"integrator.translation_block_width", "", 0, 100000, false, true, 16, false,
     "vbd: more translation levels where the finest blocks would be wider than this many "
     "vertices, up to 16 levels; 0 = exactly translation_levels", kHidden,
     [](const Scene& s) -> std::optional<double> {
         return s.integrator.method == Method::Vbd
                    ? std::optional<double>(s.integrator.translationBlockWidth) : std::nullopt;
     },
     [](Scene& s, double v) { s.integrator.translationBlockWidth = int(std::lround(v)); }},
    {"integrator.max_step_strain", "", 0, 10, false, false, 0, false,
     "a step that stretches a structural spring by more than this fraction of its rest length "
     "is redone as two of half the Δt, down to Δt/16; 0 = off", kHidden,
     [](const Scene& s) -> std::optional<double> { return s.integrator.maxStepStrain; },
     [](Scene& s, double v) { s.integrator.maxStepStrain = v; }},
    {"wind.strength", "N; N/m²", -kInf, kInf, false, false, 0, true,
     "K_w in F = K_w ⟨n, û_w⟩ n per vertex; with a material a pressure, times the vertex's area",
     {PanelSection::Wind, SliderScale::Log, 0, 100, "strength"},
     [](const Scene& s) { return s.wind ? std::optional(s.wind->strength) : std::nullopt; },
     [](Scene& s, double v) { if (s.wind) s.wind->strength = v; }},
    {"self_collision.thickness", "m", 0, 1, true, false, 0.004, true,
     "distance kept between non-neighbouring elements of the cloth; below the grid's cell size",
     {PanelSection::Forces, SliderScale::Log, 1e-4, 0.05, "self thickness [m]", "%.4f"},
     [](const Scene& s) {
         return s.selfCollision ? std::optional(s.selfCollision->thickness) : std::nullopt;
     },
     [](Scene& s, double v) { if (s.selfCollision) s.selfCollision->thickness = v; }},
    {"self_collision.friction", "", 0, kInf, false, false, 0, false,
     "Coulomb friction μ of the cloth sliding on itself",
     {PanelSection::Forces, SliderScale::Linear, 0, 2, "self friction"},
     [](const Scene& s) {
         return s.selfCollision ? std::optional(s.selfCollision->friction) : std::nullopt;
     },
     [](Scene& s, double v) { if (s.selfCollision) s.selfCollision->friction = v; }},
    {"max_speed", "m/s", 0, kInf, true, false, 1e4, false,
     "a faster vertex means the run is unstable", kHidden,
     [](const Scene& s) -> std::optional<double> { return s.maxSpeed; },
     [](Scene& s, double v) { s.maxSpeed = v; }},
    {"max_strain", "", 0, kInf, true, false, 1, false,
     "a spring stretched or squeezed by more than this fraction of its rest length means the run "
     "is unstable", kHidden,
     [](const Scene& s) -> std::optional<double> { return s.maxStrain; },
     [](Scene& s, double v) { s.maxStrain = v; }},
    {"duration", "s", 0, 1e9, true, false, 1, false,
     "simulated time `run` covers without --steps", kHidden,
     [](const Scene& s) -> std::optional<double> { return s.duration; },
     [](Scene& s, double v) { s.duration = v; }},
    // The viewer's colliders panel edits each collider's radius with the collider.
    {"colliders[].radius", "m", 0, kInf, true, false, 1, true, "sphere radius"},
};
// clang-format on

std::string number(double x) {
    if (std::isinf(x)) return x > 0 ? "∞" : "−∞";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", x);
    return buf;
}

std::string rangeText(const ParamSpec& p) {
    // Appended piece by piece: GCC 12 warns wrongly (-Wrestrict) on "literal" + string&&.
    std::string r = p.minExclusive || std::isinf(p.min) ? "(" : "[";
    r += number(p.min);
    r += ", ";
    r += number(p.max);
    r += p.maxExclusive || std::isinf(p.max) ? ")" : "]";
    if (p.integer) r += ", integer";
    return r;
}

// A "|" in a meaning would end its table cell.
std::string cell(const char* text) {
    std::string out;
    for (const char* c = text; *c; ++c) out += *c == '|' ? std::string("\\|") : std::string(1, *c);
    return out;
}

std::string sliderText(const SliderSpec& s) {
    if (s.section == PanelSection::Hidden) return "—";
    return (s.scale == SliderScale::Log ? "log " : "linear ") + number(s.min) + " … " +
           number(s.max);
}

}  // namespace

std::span<const ParamSpec> paramTable() {
    return kParams;
}

const ParamSpec* findParam(const std::string& path) {
    for (const ParamSpec& p : kParams)
        if (path == p.path) return &p;
    return nullptr;
}

const ParamSpec& paramSpec(const std::string& path) {
    if (const ParamSpec* p = findParam(path)) return *p;
    throw std::logic_error("scene/params.cpp has no row for " + path);
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
    if (spec.maxExclusive ? !(value < spec.max) : value > spec.max) {
        std::snprintf(buf, sizeof buf, "must be %s %g%s%s, got %.17g",
                      spec.maxExclusive ? "<" : "<=", spec.max, unit[0] ? " " : "", unit, value);
        return buf;
    }
    return "";
}

std::string paramsMarkdown() {
    std::string md =
        "# Scene parameters\n\n"
        "The scalar parameters of a scene file, generated from `src/scene/params.cpp` (the one\n"
        "table behind the loader's checks, `clothsim validate` and the viewer's sliders).\n"
        "Regenerate with `clothsim validate --params-markdown > docs/parameters.md`.\n\n"
        "| key | unit | valid range | default | viewer slider | meaning |\n"
        "|---|---|---|---|---|---|\n";
    for (const ParamSpec& p : kParams) {
        md += std::string("| `") + p.path + "` | " + p.unit + " | " + rangeText(p) + " | " +
              (p.required ? "required" : number(p.defaultValue)) + " | " + sliderText(p.slider) +
              " | " + cell(p.description) + " |\n";
    }
    return md;
}

}  // namespace cloth
