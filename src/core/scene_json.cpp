#include "core/scene_json.h"

#include <nlohmann/json.hpp>

namespace cloth {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const glm::dvec3& v) {
    return Json::array({v.x, v.y, v.z});
}

Json collider(const Collider& c) {
    if (const Plane* p = std::get_if<Plane>(&c))
        return {{"type", "plane"}, {"point", vec(p->point)}, {"normal", vec(p->normal)}};
    const Sphere& s = std::get<Sphere>(c);
    return {{"type", "sphere"}, {"center", vec(s.center)}, {"radius", s.radius}};
}

}  // namespace

std::string sceneToJson(const Scene& s) {
    Json j;
    j["name"] = s.name;
    j["cloth"] = {
        {"resolution", {s.cloth.nu, s.cloth.nv}}, {"size", {s.cloth.size.x, s.cloth.size.y}},
        {"origin", vec(s.cloth.origin)},          {"u_axis", vec(s.cloth.uAxis)},
        {"v_axis", vec(s.cloth.vAxis)},           {"mass", s.cloth.mass}};
    Json springs = Json::object();  // absent families stay absent: not modelled
    for (Family f : {Family::Structural, Family::Shear, Family::Bend})
        if (s.springs.of(f) > 0) springs[familyName(f)] = s.springs.of(f);
    j["springs"] = springs;
    j["damping"] = s.damping;
    j["gravity"] = vec(s.gravity);
    Json pins = Json::array();
    for (const Pin& p : s.pins) pins.push_back({p.i, p.j});
    j["pins"] = pins;
    j["integrator"] = {{"method", methodName(s.integrator.method)},
                       {"dt", s.integrator.dt},
                       {"substeps", s.integrator.substeps}};
    if (s.integrator.method == Method::ImplicitEuler) {
        j["integrator"]["tolerance"] = s.integrator.tolerance;
        j["integrator"]["max_iterations"] = s.integrator.maxIterations;
    }
    Json colliders = Json::array();
    for (const Collider& c : s.colliders) colliders.push_back(collider(c));
    j["colliders"] = colliders;
    if (s.wind) j["wind"] = {{"direction", vec(s.wind->direction)}, {"strength", s.wind->strength}};
    j["max_speed"] = s.maxSpeed;
    j["duration"] = s.duration;
    return j.dump(2) + "\n";
}

}  // namespace cloth
