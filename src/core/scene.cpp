#include "core/scene.h"

#include <algorithm>
#include <cmath>

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
    return int(std::count_if(colliders.begin(), colliders.end(),
                             [](const Collider& c) { return std::holds_alternative<Plane>(c); }));
}

int Scene::sphereCount() const {
    return int(std::count_if(colliders.begin(), colliders.end(),
                             [](const Collider& c) { return std::holds_alternative<Sphere>(c); }));
}

}  // namespace cloth
