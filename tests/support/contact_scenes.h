// Small contact scenes the CPU and GPU collider tests share (tests/cpu/collider_solver_test.cpp,
// tests/cpu/collider_drag_test.cpp and their GPU twins): a cloth resting on a box, still or
// moving; a cloth on a tilted box with friction; a vertex patch above a plain sphere; and the
// means and extremes they measure.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

namespace cloth::test {

using Json = nlohmann::json;

// The mean of the points (a cloth's mean position or velocity).
inline glm::dvec3 meanOf(const std::vector<glm::dvec3>& v) {
    glm::dvec3 m(0);
    for (const glm::dvec3& w : v) m += w;
    return m / double(v.size());
}

// The lowest y of the points [m].
inline double lowestY(const std::vector<glm::dvec3>& ps) {
    double lowest = 1e300;
    for (const glm::dvec3& p : ps) lowest = std::min(lowest, p.y);
    return lowest;
}

// A 6×6 cloth of 20 cm resting (h = 2 mm above) on a still box whose top is at y = 0.1, friction
// 0.8. Its springs are outside explicit Euler's bound, but every vertex sticks every step, which
// sets its velocity to the box's and leaves no mode to grow: the runs are stable.
inline Json clothOnBox() {
    return Json::parse(R"({
      "cloth": { "resolution": [6, 6], "size": [0.2, 0.2], "origin": [-0.1, 0.1021, -0.1],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 20.0, "shear": 5.0 },
      "damping": 0.002,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "box", "center": [0, 0, 0], "half_extents": [0.5, 0.1, 0.5],
                       "thickness": 0.002, "friction": 0.8 } ]
    })");
}

// clothOnBox with the box moving sideways at 0.3 m/s, for 1 s.
inline Json clothOnMovingBox() {
    Json j = clothOnBox();
    j["duration"] = 1.0;
    j["colliders"][0]["motion"] = {{"type", "linear"}, {"velocity", {0.3, 0, 0}}};
    return j;
}

// A 5×5 cloth, 0.1 m square, lying flat on a box tilted by θ about x (friction c_f, h = 2 mm),
// at rest, for 1 s. docs/colliders.md §2: it holds iff tan θ ≤ c_f, up to the creep of the
// seed's explicit Euler (≈ ½ g sin θ Δt m/s). The springs keep explicit Euler inside its bound
// Δt < μ/λ_max (DESIGN.md §2): λ_max ≤ 2·4·(0.1 + 0.025) = 1 N/m and μ = 0.002 give 2 ms against
// Δt = 1 ms (with K = 20 N/m the bound is 10 µs and a sliding cloth blows up near step 400).
inline Json clothOnTiltedBox(double degrees, double friction) {
    const double t = degrees * std::numbers::pi / 180;
    const double top = 0.05 + 0.002;  // the box's half height + h
    // The cloth's plane: the box's top face, tilted about x (y, z turn together).
    const glm::dvec3 up(0, std::cos(t), std::sin(t)), along(0, -std::sin(t), std::cos(t));
    const glm::dvec3 centre = top * up;
    Json j = Json::parse(R"({
      "cloth": { "resolution": [5, 5], "size": [0.1, 0.1], "mass": 0.001 },
      "springs": { "structural": 0.1, "shear": 0.025 },
      "damping": 0.002,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "duration": 1.0
    })");
    const glm::dvec3 origin = centre - 0.05 * glm::dvec3(1, 0, 0) - 0.05 * along;
    j["cloth"]["origin"] = {origin.x, origin.y, origin.z};
    j["cloth"]["u_axis"] = {1, 0, 0};
    j["cloth"]["v_axis"] = {along.x, along.y, along.z};
    j["colliders"] = Json::array({{{"type", "box"},
                                   {"center", {0, 0, 0}},
                                   {"half_extents", {1, 0.05, 1}},
                                   {"rotation", {{"axis", {1, 0, 0}}, {"degrees", degrees}}},
                                   {"thickness", 0.002},
                                   {"friction", friction}}});
    return j;
}

// A 0.6 m cotton sheet (12²) dropped 0.2 m off-centre onto a sphere (R = 0.15 m at y = 0.5 m,
// thickness 5 mm, friction c_f), its integrator given: static friction against the sheet's own
// tension holds it there (tests/cpu/implicit_contact_test.cpp).
inline Json sheetOverSphere(double friction, const Json& integrator) {
    return {{"name", "sheet over a sphere (test)"},
            {"cloth",
             {{"resolution", {12, 12}},
              {"size", {0.6, 0.6}},
              {"origin", {-0.22, 0.7, -0.3}},
              {"u_axis", {1, 0, 0}},
              {"v_axis", {0, 0, 1}}}},
            {"material", {{"preset", "cotton"}}},
            {"integrator", integrator},
            {"colliders",
             {{{"type", "sphere"},
               {"center", {0, 0.5, 0}},
               {"radius", 0.15},
               {"thickness", 0.005},
               {"friction", friction}}}}};
}

// A 5×5 sheet of 20 cm lying flat `depth` under a plane y = 0 (no thickness or friction), the
// plane moving up at `rise` m/s, at Δt = 1 ms by `method`.
inline Json sheetUnderPlane(double depth, double rise, const char* method = "implicit_euler") {
    Json j = {{"name", "sheet under a plane (test)"},
              {"cloth",
               {{"resolution", {5, 5}},
                {"size", {0.2, 0.2}},
                {"origin", {-0.1, -depth, -0.1}},
                {"u_axis", {1, 0, 0}},
                {"v_axis", {0, 0, 1}}}},
              {"material", {{"density", 0.2}, {"stretch", 100}, {"shear", 10}}},
              {"integrator", {{"method", method}, {"dt", 0.001}}},
              {"colliders", {{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}}}};
    if (rise != 0) j["colliders"][0]["motion"] = {{"type", "linear"}, {"velocity", {0, rise, 0}}};
    return j;
}

// A 3×3 patch of 2 cm at y = 0.5, without gravity, 1 cm above a plain sphere (DESIGN.md §2's
// rule, v_c = 0) of radius 0.49 at the origin.
inline const char* const kPatchAbovePlainSphere = R"({
      "cloth": { "resolution": [3, 3], "size": [0.02, 0.02], "origin": [-0.01, 0.5, -0.01],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1], "mass": 0.001 },
      "springs": { "structural": 10.0 }, "damping": 0.001, "gravity": [0, 0, 0],
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "colliders": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.49 } ]
    })";

}  // namespace cloth::test
