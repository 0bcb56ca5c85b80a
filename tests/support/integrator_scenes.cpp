#include "support/integrator_scenes.h"

#include <cmath>
#include <cstdio>
#include <variant>

#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "support/reference_bridge.h"

namespace cloth {

Scene springScene(const DampedSpring& s, Method method, double dt, double tolerance) {
    char text[640];
    std::snprintf(text, sizeof text, R"({
      "cloth": { "resolution": [1, 2], "size": [1.0, 1.0], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": %.17g },
      "springs": { "structural": %.17g },
      "damping": %.17g,
      "gravity": [0, %.17g, 0],
      "pins": [[0, 0]],
      "integrator": { "method": "%s", "dt": %.17g, "tolerance": %.17g, "max_iterations": 50 }
    })",
                  s.m, s.k, s.mu, -s.g, methodName(method), dt, tolerance);
    return parseScene(text, "spring (test)");
}

SimState springState(double x, double xDot) {
    SimState st;
    st.nu = 1;
    st.nv = 2;
    st.positions = {glm::dvec3(0), glm::dvec3(0, -1 - x, 0)};
    st.velocities = {glm::dvec3(0), glm::dvec3(0, -xDot, 0)};
    return st;
}

// The floor is axis-aligned at a dyadic height so that a vertex resting on it sits at s = 0
// exactly after its projection (see reference_parity_test.cpp): two correct implementations
// then decide "s < 0" alike.
Scene everythingScene(Method method, double dt) {
    Scene s = parseScene(R"({
      "name": "everything-small",
      "cloth": { "resolution": [9, 13], "size": [1.2, 1.7], "origin": [-0.6, 1.0, -0.85],
                 "u_axis": [2, 0, 0.2], "v_axis": [0, 0.1, 1], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1], [4, -1]],
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "plane", "point": [0, 0.25, 0], "normal": [0, 2, 0] },
                     { "type": "sphere", "center": [0.05, 0.6, -0.1], "radius": 0.3 } ],
      "wind": { "direction": [1, 0.2, 0.6], "strength": 2.0 },
      "max_speed": 10000.0
    })",
                         "everything-small (test)");
    s.integrator.method = method;
    s.integrator.dt = dt;
    return s;
}

long firstContactStep(const Scene& scene, long steps) {
    ref::Simulation sim(toReference(scene));
    for (long n = 1; n <= steps; ++n) {
        sim.step();
        for (const ref::V3& x : sim.positions()) {
            const glm::dvec3 q(x[0], x[1], x[2]);
            for (const Collider& c : scene.colliders) {
                double outside;
                if (const Plane* p = c.as<Plane>())
                    outside = glm::dot(q - p->point, p->normal);
                else
                    outside = glm::length(q - c.as<Sphere>()->center) - c.as<Sphere>()->radius;
                if (outside < 1e-9) return n;
            }
        }
    }
    return 0;
}

}  // namespace cloth
