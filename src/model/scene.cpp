#include "model/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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
    }
    return 1;
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

long Scene::defaultSteps() const {
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
