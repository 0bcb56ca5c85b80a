#include "model/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "model/errors.h"

namespace cloth {

const char* methodName(Method m) {
    switch (m) {
        case Method::ExplicitEuler:
            return "explicit_euler";
        case Method::SymplecticEuler:
            return "symplectic_euler";
        case Method::Verlet:
            return "verlet";
        case Method::Rk4:
            return "rk4";
        case Method::ImplicitEuler:
            return "implicit_euler";
        case Method::Vbd:
            return "vbd";
    }
    return "?";
}

std::optional<Method> methodFromName(const std::string& name) {
    for (Method m : kMethods)
        if (name == methodName(m)) return m;
    return std::nullopt;
}

std::string methodList() {
    std::string s;
    for (Method m : kMethods) s += std::string(s.empty() ? "" : ", ") + methodName(m);
    return s;
}

int forceEvaluationsPerStep(Method m) {
    switch (m) {
        case Method::Rk4:
            return 4;
        case Method::ExplicitEuler:
        case Method::SymplecticEuler:
        case Method::Verlet:  // F(x_{n+1}) of one step is F(x_n) of the next
        case Method::ImplicitEuler:
            return 1;
        case Method::Vbd:  // per iteration: its sweep gathers every vertex's springs once
            return 1;
    }
    return 1;
}

const char* preconditionerName(Preconditioner p) {
    switch (p) {
        case Preconditioner::None:
            return "none";
        case Preconditioner::Jacobi:
            return "jacobi";
        case Preconditioner::Multigrid:
            return "multigrid";
        case Preconditioner::Aggregation:
            return "aggregation";
    }
    return "?";
}

std::vector<std::string> unusedIntegratorSettings(const IntegratorSpec& in) {
    const IntegratorSpec defaults;
    const std::string method = methodName(in.method);
    std::vector<std::string> lines;
    auto unused = [&](const std::string& key, const std::string& value, const char* owner,
                      const char* instead) {
        lines.push_back("integrator." + key + " = " + value + " is " + owner + "'s; " + method +
                        " does not use it" + instead);
    };
    char value[32];
    if (in.method != Method::ImplicitEuler) {
        const char* instead = in.method == Method::Vbd ? " (vbd's sweeps a step: iterations)" : "";
        std::snprintf(value, sizeof value, "%g", in.tolerance);
        if (in.tolerance != defaults.tolerance) unused("tolerance", value, "implicit_euler", "");
        if (in.maxIterations != defaults.maxIterations)
            unused("max_iterations", std::to_string(in.maxIterations), "implicit_euler", instead);
        if (in.preconditioner != defaults.preconditioner)
            unused("preconditioner",
                   std::string("\"") + preconditionerName(in.preconditioner) + "\"",
                   "implicit_euler", "");
    }
    if (in.method != Method::Vbd) {
        const char* instead =
            in.method == Method::ImplicitEuler ? " (the CG's cap: max_iterations)" : "";
        if (in.iterations != defaults.iterations)
            unused("iterations", std::to_string(in.iterations), "vbd", instead);
        std::snprintf(value, sizeof value, "%g", in.chebyshevRho);
        if (in.chebyshevRho != defaults.chebyshevRho) unused("chebyshev_rho", value, "vbd", "");
        if (in.translationSweeps != defaults.translationSweeps)
            unused("translation_sweeps", std::to_string(in.translationSweeps), "vbd", "");
        if (in.translationLevels != defaults.translationLevels)
            unused("translation_levels", std::to_string(in.translationLevels), "vbd", "");
        if (in.translationLevelPasses != defaults.translationLevelPasses)
            unused("translation_level_passes", std::to_string(in.translationLevelPasses), "vbd",
                   "");
        if (in.translationBlockWidth != defaults.translationBlockWidth)
            unused("translation_block_width", std::to_string(in.translationBlockWidth), "vbd", "");
    } else if (in.translationLevels == 0 && in.translationLevelPasses != 1) {
        lines.push_back(
            "integrator.translation_level_passes = " + std::to_string(in.translationLevelPasses) +
            " repeats the translation's levels; translation_levels = 0 runs none");
    } else if (in.translationLevelPasses > in.iterations) {
        lines.push_back(
            "integrator.translation_level_passes = " + std::to_string(in.translationLevelPasses) +
            " is more than the " + std::to_string(in.iterations) +
            " sweeps a step: the levels run once before each sweep");
    }
    return lines;
}

std::optional<Preconditioner> preconditionerFromName(const std::string& name) {
    for (Preconditioner p : kPreconditioners)
        if (name == preconditionerName(p)) return p;
    return std::nullopt;
}

double SpringStiffness::of(Family f) const {
    switch (f) {
        case Family::Structural:
            return structural;
        case Family::Shear:
            return shear;
        case Family::Bend:
            return bend;
    }
    return 0;
}

Grid Scene::grid() const {
    Grid g;
    g.nu = cloth.nu;
    g.nv = cloth.nv;
    g.du = cloth.nu > 1 ? cloth.size.x / (cloth.nu - 1) : 0.0;  // DESIGN.md §2
    g.dv = cloth.nv > 1 ? cloth.size.y / (cloth.nv - 1) : 0.0;
    g.origin = cloth.origin;
    g.u = cloth.uAxis;
    g.v = cloth.vAxis;
    return g;
}

// docs/physics.md, "From a material to the grid": with K_d on both diagonals of a du × dv cell,
// the lattice's constants are C₁₂ = C₆₆ = 2K_d du dv/ℓ² (ℓ² = du² + dv²), C₁₁ = K_u du/dv +
// G du²/dv², C₂₂ = K_v dv/du + G dv²/du². C₆₆ = G fixes K_d; uniaxial tension along u or v
// (sides free) has stiffness C − G²/C = Y when C₁₁ = C₂₂ = C = (Y + √(Y² + 4G²))/2.
MembraneSprings membraneSprings(const Material& m, double du, double dv) {
    const double l2 = du * du + dv * dv;
    const double c = (m.stretch + std::sqrt(m.stretch * m.stretch + 4 * m.shear * m.shear)) / 2;
    MembraneSprings k;
    k.shear = m.shear * l2 / (2 * du * dv);
    k.alongU = (c - m.shear * du * du / (dv * dv)) * dv / du;
    k.alongV = (c - m.shear * dv * dv / (du * du)) * du / dv;
    return k;
}

double Scene::vertexMass(int i, int j) const {
    if (!material) return cloth.mass;
    const Grid g = grid();
    const double shareU = (i == 0 || i == g.nu - 1) ? 0.5 : 1.0;
    const double shareV = (j == 0 || j == g.nv - 1) ? 0.5 : 1.0;
    return material->density * (g.du * shareU) * (g.dv * shareV);
}

double Scene::windArea(int i, int j) const {
    if (!material) return 1;
    const Grid g = grid();
    const double shareU = (i == 0 || i == g.nu - 1) ? 0.5 : 1.0;
    const double shareV = (j == 0 || j == g.nv - 1) ? 0.5 : 1.0;
    return (g.du * shareU) * (g.dv * shareV);
}

double Scene::totalMass() const {
    if (!material) return cloth.mass * cloth.nu * cloth.nv;
    return material->density * cloth.size.x * cloth.size.y;
}

double Scene::slotStiffness(int slot) const {
    const SpringOffset& o = kSpringOffsets[std::size_t(slot)];
    if (!material) return springs.of(o.family);
    const Grid g = grid();
    const MembraneSprings k = membraneSprings(*material, g.du, g.dv);
    switch (o.family) {
        case Family::Structural:
            return o.di != 0 ? k.alongU : k.alongV;
        case Family::Shear:
            return k.shear;
        case Family::Bend:
            return 0;  // bending is the quadratic energy of bendingStiffness()
    }
    return 0;
}

double Scene::dampingRate() const {
    return material ? material->airDamping : damping / cloth.mass;
}

double Scene::bendingStiffness() const {
    return material ? material->bend : 0.0;
}

double Scene::springDamping() const {
    return material ? material->springDamping : 0.0;
}

long Scene::defaultSteps() const {
    // Checked here, where the duration is used: a run given its steps (--steps, Python) does not
    // need the duration's count of them.
    if (!(duration / integrator.dt <= 1e12))
        throw InputError(source, "duration",
                         "needs more than 1e12 steps of integrator.dt; give the run --steps");
    return std::max(1L, std::lround(duration / integrator.dt));
}

int Scene::planeCount() const {
    return count<Plane>();
}

int Scene::sphereCount() const {
    return count<Sphere>();
}

glm::dmat3 AxisAngle::matrix() const {
    return axisAngle(axis, degrees * std::numbers::pi / 180);
}

Motion ColliderMotion::motion() const {
    Motion m;
    m.type = type;
    m.velocity = velocity;
    m.axis = axis;
    m.pivot = pivot;
    m.angularSpeed = degreesPerSecond * std::numbers::pi / 180;
    m.amplitude = amplitude;
    m.frequency = frequency;
    m.phase = phaseDegrees * std::numbers::pi / 180;
    return m;
}

const char* colliderTypeName(const ColliderShape& shape) {
    static constexpr const char* kNames[] = {"plane", "sphere", "box", "capsule", "mesh"};
    return kNames[shape.index()];
}

}  // namespace cloth
