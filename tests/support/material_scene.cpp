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
      "wind": { "direction": [1, 0.2, 0.6], "strength": 0.2 }
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
    const Grid g = probe.grid();
    auto share = [](int i, int n) { return i == 0 || i == n - 1 ? 0.5 : 1.0; };
    std::vector<double> m;
    for (std::size_t k = 0; k < afterOneStep.velocities.size(); ++k) {
        const int i = int(k % std::size_t(g.nu)), j = int(k / std::size_t(g.nu));
        const double area = g.du * share(i, g.nu) * g.dv * share(j, g.nv);
        m.push_back(probe.integrator.dt * probe.wind->strength * area /
                    glm::length(afterOneStep.velocities[k]));
    }
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

Scene windSheetScene(int cells) {
    Scene s = parseScene(R"({
      "name": "wind sheet",
      "cloth": { "resolution": [8, 6], "size": [1.0, 0.75], "origin": [0, 1, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1] },
      "material": { "preset": "cotton" },
      "gravity": [0, 0, 0],
      "integrator": { "method": "symplectic_euler", "dt": 0.0001 },
      "wind": { "direction": [0.8660254037844386, 0.5, 0], "strength": 10 }
    })",
                         "wind sheet (test)");
    s.cloth.nu = cells + 1;
    s.cloth.nv = 3 * cells / 4 + 1;
    return s;
}

WindImpulse windImpulse(const Scene& scene, const SimState& afterOneStep) {
    const Grid g = scene.grid();
    const glm::dvec3 normal = glm::normalize(glm::cross(g.u, g.v));
    double momentum = 0, mean = 0;
    const auto& v = afterOneStep.velocities;
    for (std::size_t k = 0; k < v.size(); ++k) {
        const int i = int(k % std::size_t(g.nu)), j = int(k / std::size_t(g.nu));
        momentum += scene.vertexMass(i, j) * glm::dot(v[k], normal);
        mean += glm::length(v[k]) / double(v.size());
    }
    const double cosine = std::abs(glm::dot(normal, scene.wind->direction));
    const double area = scene.cloth.size.x * scene.cloth.size.y;
    WindImpulse w;
    w.ofPressure =
        std::abs(momentum) / (scene.integrator.dt * scene.wind->strength * area * cosine);
    for (const glm::dvec3& vk : v)
        w.spread = std::max(w.spread, std::abs(glm::length(vk) / mean - 1));
    return w;
}

}  // namespace cloth
