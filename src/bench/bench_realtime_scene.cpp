#include "bench/bench_realtime_scene.h"

#include <nlohmann/json.hpp>

#include "scene/scene_loader.h"

namespace cloth::app {

Scene realtimeDrape(const std::string& material, int n, double time,
                    const std::vector<std::string>& sets) {
    using Json = nlohmann::json;
    // The sheet falls 0.3 m onto the sphere's top (about 0.25 s), then drapes over it; its
    // corners, 0.71 m from the centre, reach the ground. Δt and the integrator are set per trial.
    const Json doc = {{"name", "drape_" + material},
                      {"cloth",
                       {{"resolution", {n, n}},
                        {"size", {1.0, 1.0}},
                        {"origin", {-0.5, 0.8, -0.5}},
                        {"u_axis", {1, 0, 0}},
                        {"v_axis", {0, 0, 1}}}},
                      {"material", {{"preset", material}}},
                      {"integrator", {{"method", "symplectic_euler"}, {"dt", 1.0 / 60}}},
                      {"colliders",
                       {{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 1, 0}}},
                        {{"type", "sphere"}, {"center", {0, 0.25, 0}}, {"radius", 0.25}}}},
                      {"duration", time}};
    return parseScene(doc.dump(), "bench realtime drape (--material " + material + ")", sets);
}

Scene perVertexForm(const Scene& scene) {
    if (!scene.material) return scene;
    const Material& m = *scene.material;
    const Grid g = scene.grid();
    const MembraneSprings k = membraneSprings(m, g.du, g.dv);
    Scene s = scene;
    s.material.reset();
    s.cloth.mass = m.density * g.du * g.dv;
    s.springs = {0.5 * (k.alongU + k.alongV), k.shear, 0};
    s.damping = m.airDamping * s.cloth.mass;
    return s;
}

}  // namespace cloth::app
