// The collider cases the CPU and GPU collider tests share (tests/cpu/collider_solver_test.cpp,
// tests/gpu/gpu_collider_solver_test.cpp, tests/gpu/gpu_collider_contact_test.cpp): every shape
// alone and combined, with thickness, friction and motion; the mesh collider's OBJ; the GPU's
// falling cloth, whose Δt is inside explicit Euler's bound so that every integrator runs the same
// scene; and the reference's measure of how deep a vertex is inside a collider.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/collider_mesh.h"
#include "reference/reference_colliders.h"
#include "scene/scene_loader.h"
#include "support/process.h"

namespace cloth::test {

using Json = nlohmann::json;

// A 13×11 cloth, 0.6 m × 0.5 m, level at y = 0.95, falling from rest onto colliders 0.05–0.2 m
// below. Explicit Euler's bound Δt < μ/λ_max (DESIGN.md §2) with λ_max ≤ 2·4·(80 + 25 + 5) =
// 880 N/m and μ = 0.5: 0.57 ms > Δt = 0.5 ms; c = μ/m = 10/s, so the cloth falls ~0.3 m in 0.4 s.
inline Json fallingClothOnColliders(const Json& colliders, const char* method) {
    Json j = Json::parse(R"({
      "cloth": { "resolution": [13, 11], "size": [0.6, 0.5], "origin": [-0.3, 0.95, -0.25],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.05 },
      "springs": { "structural": 80.0, "shear": 25.0, "bend": 5.0 },
      "damping": 0.5,
      "integrator": { "dt": 0.0005 },
      "duration": 0.4
    })");
    j["integrator"]["method"] = method;
    j["colliders"] = colliders;
    return j;
}

// An OBJ of a closed box (0.5 × 0.1 × 0.4) in `dir`, written by the project itself, for the mesh
// collider ("slab.obj").
inline void writeSlabObj(const std::filesystem::path& dir) {
    writeMeshesObj((dir / "slab.obj").string(),
                   {{"slab", boxMesh({{0, 0, 0}, {0.25, 0.05, 0.2}, glm::dmat3(1)})}});
}

struct ColliderCase {
    std::string name;
    Json colliders;
};

// Each shape alone (plain, then with thickness and friction), each motion, and all five
// together. A cloth starting 0.1–0.3 m above them lands within the run.
inline std::vector<ColliderCase> colliderCases() {
    const Json box = {{"type", "box"},
                      {"center", {0.02, 0.7, 0.01}},
                      {"half_extents", {0.2, 0.05, 0.15}},
                      {"rotation", {{"axis", {1, 0, 0.3}}, {"degrees", 12}}}};
    const Json capsule = {{"type", "capsule"},
                          {"a", {-0.25, 0.8, 0.05}},
                          {"b", {0.2, 0.75, -0.05}},
                          {"radius", 0.08}};
    const Json mesh = {{"type", "mesh"},
                       {"file", "slab.obj"},
                       {"cell", 0.02},
                       {"band", 0.06},
                       {"translation", {0, 0.75, 0}},
                       {"rotation", {{"axis", {0, 0, 1}}, {"degrees", 8}}}};
    const Json plane = {{"type", "plane"}, {"point", {0, 0.85, 0}}, {"normal", {0.1, 1, 0}}};
    const Json sphere = {{"type", "sphere"}, {"center", {0.05, 0.7, 0}}, {"radius", 0.2}};
    auto with = [](Json c, const Json& extra) {
        c.update(extra);
        return c;
    };
    const Json contact = {{"thickness", 0.01}, {"friction", 0.4}};
    const Json rising = {{"motion", {{"type", "linear"}, {"velocity", {0.1, 0.5, 0}}}}};
    const Json turning = {{"motion",
                           {{"type", "rotation"},
                            {"axis", {0, 1, 0}},
                            {"pivot", {0, 0, 0}},
                            {"degrees_per_second", 90}}}};
    const Json swinging = {{"motion",
                            {{"type", "oscillation"},
                             {"axis", {1, 0, 0}},
                             {"amplitude", 0.05},
                             {"frequency", 2},
                             {"phase_degrees", 30}}}};
    return {
        {"box", Json::array({box})},
        {"capsule", Json::array({capsule})},
        {"mesh", Json::array({mesh})},
        {"plane_thickness_friction", Json::array({with(plane, contact)})},
        {"sphere_thickness_friction", Json::array({with(sphere, contact)})},
        {"box_friction_rising", Json::array({with(with(box, contact), rising)})},
        {"capsule_turning", Json::array({with(with(capsule, contact), turning)})},
        {"sphere_swinging", Json::array({with(sphere, swinging)})},
        {"mesh_friction_turning", Json::array({with(with(mesh, contact), turning)})},
        {"all_combined", Json::array({with(box, contact), with(capsule, turning),
                                      with(mesh, Json{{"thickness", 0.005}}),
                                      with(sphere, swinging), with(plane, rising)})},
    };
}

// The distance of p inside any collider of the reference at time t, beyond its thickness
// (≤ 0; 0 when every vertex is on or outside every offset surface φ = h): the reference's own
// shapes (no code shared with src/). A probe vertex at rest that the reference's collideMoving()
// pushes out moves by exactly that much.
inline double worstPenetration(const ref::Params& prm, double t,
                               const std::vector<glm::dvec3>& ps) {
    double worst = 0;
    for (const ref::Collider& c : prm.colliders) {
        ref::Collider probe = c;
        probe.extended = true;
        probe.friction = 0;
        for (const glm::dvec3& q : ps) {
            ref::V3 p{q.x, q.y, q.z}, v{0, 0, 0};
            ref::collideMoving(probe, t, p, v);
            worst = std::min(worst, -std::hypot(p[0] - q.x, p[1] - q.y, p[2] - q.z));
        }
    }
    return worst;
}

}  // namespace cloth::test
