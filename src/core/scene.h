// A validated scene: what the simulation models, in SI units (DESIGN.md §4). Only what the file
// declares is here; a family of stiffness 0, an absent wind or an empty collider list is not
// modelled at all.
#pragma once

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/grid.h"

namespace cloth {

// The integrators of docs/integrators.md. explicit_euler is the seed's scheme (DESIGN.md §2).
enum class Method { ExplicitEuler, SymplecticEuler, Verlet, Rk4, ImplicitEuler };

inline constexpr Method kMethods[] = {Method::ExplicitEuler, Method::SymplecticEuler,
                                      Method::Verlet, Method::Rk4, Method::ImplicitEuler};

const char* methodName(Method m);  // "explicit_euler", ...
std::optional<Method> methodFromName(const std::string& name);
std::string methodList();               // "explicit_euler, symplectic_euler, ..."
int forceEvaluationsPerStep(Method m);  // spring-force passes one step costs (implicit: + CG)

struct ClothSpec {
    int nu = 2, nv = 2;                         // vertices along u and v
    glm::dvec2 size{1, 1};                      // extent along û and v̂ [m]
    glm::dvec3 origin{0};                       // position of vertex (0, 0) [m]
    glm::dvec3 uAxis{1, 0, 0}, vAxis{0, 0, 1};  // normalised by the loader
    double mass = 1;                            // per vertex [kg]
};

struct SpringStiffness {
    double structural = 0, shear = 0, bend = 0;  // [N/m]; 0 = family not modelled
    double of(Family f) const;
};

struct IntegratorSpec {
    Method method = Method::ExplicitEuler;
    double dt = 1e-3;  // [s]
    int substeps = 1;  // steps per displayed frame in the viewer
    // implicit_euler only: the conjugate gradient stops at |r| <= tolerance·|b| or after
    // maxIterations (then the step goes on with the last iterate and the miss is reported).
    double tolerance = 1e-5;
    int maxIterations = 200;
};

struct Plane {
    glm::dvec3 point{0}, normal{0, 1, 0};  // normal is unit length
};
struct Sphere {
    glm::dvec3 center{0};
    double radius = 1;  // [m]
};
using Collider = std::variant<Plane, Sphere>;

struct Wind {
    glm::dvec3 direction{1, 0, 0};  // unit length
    double strength = 0;            // K_w [N]
};

struct Pin {
    int i, j;  // resolved grid indices (negative ones in the file count from the end)
};

struct Scene {
    std::string name;
    std::string source;  // the file it was loaded from, for messages
    ClothSpec cloth;
    SpringStiffness springs;
    double damping = 0;  // μ [N·s/m]
    glm::dvec3 gravity{0, -9.81, 0};
    std::vector<Pin> pins;
    IntegratorSpec integrator;
    std::vector<Collider> colliders;
    std::optional<Wind> wind;
    double maxSpeed = 1e4;  // [m/s]; faster is reported as unstable
    double duration = 1;    // simulated time `run` covers without --steps [s]

    Grid grid() const;
    long defaultSteps() const;  // round(duration / dt), at least 1
    int planeCount() const;
    int sphereCount() const;
};

}  // namespace cloth
