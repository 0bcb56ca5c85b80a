#include "scene/scene_json.h"

#include <nlohmann/json.hpp>

namespace cloth {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const glm::dvec3& v) {
    return Json::array({v.x, v.y, v.z});
}

Json rotation(const AxisAngle& r) {
    return {{"axis", vec(r.axis)}, {"degrees", r.degrees}};
}

Json shape(const ColliderShape& shape) {
    if (const Plane* p = std::get_if<Plane>(&shape))
        return {{"type", "plane"}, {"point", vec(p->point)}, {"normal", vec(p->normal)}};
    if (const Sphere* s = std::get_if<Sphere>(&shape))
        return {{"type", "sphere"}, {"center", vec(s->center)}, {"radius", s->radius}};
    if (const Box* b = std::get_if<Box>(&shape))
        return {{"type", "box"},
                {"center", vec(b->center)},
                {"half_extents", vec(b->halfExtents)},
                {"rotation", rotation(b->rotation)}};
    if (const Capsule* c = std::get_if<Capsule>(&shape))
        return {{"type", "capsule"}, {"a", vec(c->a)}, {"b", vec(c->b)}, {"radius", c->radius}};
    const MeshCollider& m = std::get<MeshCollider>(shape);
    // The absolute path: a saved scene may live in another folder than the one it came from.
    return {{"type", "mesh"},
            {"file", m.path},
            {"cell", m.cell},
            {"band", m.band},
            {"translation", vec(m.translation)},
            {"rotation", rotation(m.rotation)}};
}

Json motion(const ColliderMotion& m) {
    switch (m.type) {
        case MotionType::Linear:
        case MotionType::Still:
            return {{"type", "linear"}, {"velocity", vec(m.velocity)}};
        case MotionType::Rotation:
            return {{"type", "rotation"},
                    {"axis", vec(m.axis)},
                    {"pivot", vec(m.pivot)},
                    {"degrees_per_second", m.degreesPerSecond}};
        case MotionType::Oscillation:
            return {{"type", "oscillation"},
                    {"axis", vec(m.axis)},
                    {"amplitude", m.amplitude},
                    {"frequency", m.frequency},
                    {"phase_degrees", m.phaseDegrees}};
    }
    return {};
}

// Keys at their defaults stay absent, so a scene without them saves as it did before.
Json collider(const Collider& c) {
    Json j = shape(c.shape);
    if (c.thickness != 0) j["thickness"] = c.thickness;
    if (c.friction != 0) j["friction"] = c.friction;
    if (c.motion) j["motion"] = motion(*c.motion);
    return j;
}

}  // namespace

std::string sceneToJson(const Scene& s) {
    Json j;
    j["name"] = s.name;
    j["cloth"] = {{"resolution", {s.cloth.nu, s.cloth.nv}},
                  {"size", {s.cloth.size.x, s.cloth.size.y}},
                  {"origin", vec(s.cloth.origin)},
                  {"u_axis", vec(s.cloth.uAxis)},
                  {"v_axis", vec(s.cloth.vAxis)}};
    if (const std::optional<Material>& m = s.material) {
        // Every value written out: the preset's name is kept for the reader, the values win.
        Json material = Json::object();
        if (!m->preset.empty()) material["preset"] = m->preset;
        material["density"] = m->density;
        material["stretch"] = m->stretch;
        material["shear"] = m->shear;
        material["bend"] = m->bend;
        material["air_damping"] = m->airDamping;
        material["spring_damping"] = m->springDamping;
        j["material"] = material;
    } else {
        j["cloth"]["mass"] = s.cloth.mass;
        Json springs = Json::object();  // absent families stay absent: not modelled
        for (Family f : {Family::Structural, Family::Shear, Family::Bend})
            if (s.springs.of(f) > 0) springs[familyName(f)] = s.springs.of(f);
        j["springs"] = springs;
        j["damping"] = s.damping;
    }
    j["gravity"] = vec(s.gravity);
    Json pins = Json::array();
    for (const Pin& p : s.pins) {
        if (p.follow < 0)
            pins.push_back({p.i, p.j});
        else
            pins.push_back({{"at", {p.i, p.j}}, {"follow", p.follow}});
    }
    j["pins"] = pins;
    j["integrator"] = {{"method", methodName(s.integrator.method)},
                       {"dt", s.integrator.dt},
                       {"substeps", s.integrator.substeps}};
    if (s.integrator.method == Method::ImplicitEuler) {
        j["integrator"]["tolerance"] = s.integrator.tolerance;
        j["integrator"]["max_iterations"] = s.integrator.maxIterations;
        j["integrator"]["preconditioner"] = preconditionerName(s.integrator.preconditioner);
    }
    if (s.integrator.method == Method::Vbd) {
        j["integrator"]["iterations"] = s.integrator.iterations;
        j["integrator"]["chebyshev_rho"] = s.integrator.chebyshevRho;
        j["integrator"]["translation_sweeps"] = s.integrator.translationSweeps;
        j["integrator"]["translation_levels"] = s.integrator.translationLevels;
        j["integrator"]["translation_level_passes"] = s.integrator.translationLevelPasses;
        j["integrator"]["translation_block_width"] = s.integrator.translationBlockWidth;
    }
    if (s.integrator.maxStepStrain > 0)
        j["integrator"]["max_step_strain"] = s.integrator.maxStepStrain;
    Json colliders = Json::array();
    for (const Collider& c : s.colliders) colliders.push_back(collider(c));
    j["colliders"] = colliders;
    if (s.wind) j["wind"] = {{"direction", vec(s.wind->direction)}, {"strength", s.wind->strength}};
    if (s.selfCollision)
        j["self_collision"] = {{"thickness", s.selfCollision->thickness},
                               {"friction", s.selfCollision->friction}};
    j["max_speed"] = s.maxSpeed;
    j["max_strain"] = s.maxStrain;
    j["duration"] = s.duration;
    return j.dump(2) + "\n";
}

}  // namespace cloth
