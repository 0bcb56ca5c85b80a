#include "support/material_scene.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "model/vertex_masses.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"

namespace cloth {
namespace {

Material fabric(double airDamping) {
    Material m;
    m.density = 0.15;
    m.stretch = 5000;
    m.shear = 500;
    m.airDamping = airDamping;
    return m;
}

}  // namespace

Scene materialScene(Method method, double dt) {
    Scene s = parseScene(R"({
      "name": "material",
      "cloth": { "resolution": [16, 12], "size": [1.2, 0.66], "origin": [-0.6, 1.0, -0.3],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0.3, 1] },
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]],
      "integrator": { "method": "symplectic_euler", "dt": 0.0001 },
      "wind": { "direction": [1, 0.2, 0.6], "strength": 0.001 }
    })",
                         "material (test)");
    s.material = fabric(0.1);
    s.integrator.method = method;
    s.integrator.dt = dt;
    return s;
}

Scene fallingMaterialScene(Method method, double airDamping, double dt) {
    Scene s = materialScene(method, dt);
    s.name = "falling material";
    s.pins.clear();
    s.wind.reset();
    s.gravity = {0, -9.81, 0};
    s.material->airDamping = airDamping;
    return s;
}

FallingSheet fallingSheet(const Scene& scene, const SimState& state) {
    const std::vector<double> m = vertexMasses(scene);
    FallingSheet f;
    double total = 0;
    for (std::size_t k = 0; k < m.size(); ++k) {
        f.velocity += m[k] * state.velocities[k];
        total += m[k];
    }
    f.velocity /= total;
    f.sideways = glm::length(glm::dvec2(f.velocity.x, f.velocity.z));
    for (const glm::dvec3& v : state.velocities)
        f.spread = std::max(f.spread, glm::length(v - f.velocity));
    f.strain = largestStrain(scene, state).strain;
    return f;
}

Scene massProbeScene(const Scene& scene) {
    Scene s = scene;
    s.pins.clear();
    s.gravity = glm::dvec3(0);
    s.wind = Wind{glm::normalize(glm::cross(s.cloth.uAxis, s.cloth.vAxis)), kProbeWind};
    s.integrator.method = Method::SymplecticEuler;
    return s;
}

std::vector<double> probedMasses(const Scene& probe, const SimState& afterOneStep) {
    std::vector<double> m;
    for (const glm::dvec3& v : afterOneStep.velocities)
        m.push_back(probe.integrator.dt * probe.wind->strength / glm::length(v));
    return m;
}

std::vector<double> stepMasses(Solver& solver, const Scene& probe) {
    const StepResult r = solver.step(1);
    EXPECT_FALSE(r.unstable) << r.reason;
    return probedMasses(probe, solver.read());
}

void expectLumpedMasses(const Scene& probe, double density, const std::vector<double>& m,
                        double tolerance, const std::string& what) {
    const Grid g = probe.grid();
    const double cell = density * g.du * g.dv;
    const glm::dvec3 centroid =
        g.origin + 0.5 * probe.cloth.size.x * g.u + 0.5 * probe.cloth.size.y * g.v;
    double total = 0;
    glm::dvec3 moment(0);
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) {
            const double share =
                (i == 0 || i == g.nu - 1 ? 0.5 : 1.0) * (j == 0 || j == g.nv - 1 ? 0.5 : 1.0);
            const double mk = m[std::size_t(g.index(i, j))];
            EXPECT_NEAR(mk, share * cell, tolerance * cell)
                << what << " (" << i << ", " << j << ")";
            total += mk;
            moment += mk * g.restPosition(i, j);
        }
    const double expected = density * probe.cloth.size.x * probe.cloth.size.y;
    EXPECT_NEAR(total, expected, tolerance * expected) << what;
    EXPECT_LT(glm::length(moment / total - centroid), tolerance * g.extent()) << what;
}

}  // namespace cloth
