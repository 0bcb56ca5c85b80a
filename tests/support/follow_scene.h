// The follow-pin scene the CPU and GPU pin tests share (tests/cpu/pin_follow_test.cpp,
// tests/gpu/gpu_pin_follow_test.cpp; docs/colliders.md §5) and the capsule motions it runs.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "scene/scene_loader.h"

namespace cloth::test {

using Json = nlohmann::json;

// A 7 × 5 cloth hanging from a capsule that moves by `motion`; pins (0, 0) and (-1, 0) follow
// the capsule (colliders[1]), (3, 0) is still. The capsule sits just above the top row. Every
// integrator inside its bound (DESIGN.md §2, λ_max ≤ 2·4·(200 + 50 + 5) = 2040 N/m): explicit
// Euler needs Δt < μ/λ_max, so it gets μ = 4 (2 ms; cΔt = 0.4 < 2) where μ = 0.02 (10 µs) blew
// up at step 289 with the swinging capsule.
inline Json followScene(const Json& motion, const char* method = "symplectic_euler") {
    Json j = Json::parse(R"({
      "cloth": { "resolution": [7, 5], "size": [0.6, 0.4], "origin": [-0.3, 1.0, 0.1],
                 "u_axis": [1, 0, 0], "v_axis": [0, -1, 0], "mass": 0.01 },
      "springs": { "structural": 200, "shear": 50, "bend": 5 }, "damping": 0.02,
      "pins": [ {"at": [0, 0], "follow": 1}, [3, 0], {"at": [-1, 0], "follow": 1} ],
      "integrator": { "dt": 0.001 }, "duration": 0.3,
      "colliders": [
        { "type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0] },
        { "type": "capsule", "a": [-0.3, 1.08, 0.1], "b": [0.3, 1.08, 0.1], "radius": 0.05,
          "thickness": 0.005, "friction": 0.3 } ]
    })");
    j["integrator"]["method"] = method;
    if (std::string(method) == "explicit_euler") j["damping"] = 4.0;
    j["colliders"][1]["motion"] = motion;
    return j;
}

// The capsule's motions: turning about a vertical axis off its centre, walking, swinging.
inline const Json kTurning = Json::parse(
    R"({"type": "rotation", "axis": [0, 1, 0], "pivot": [0.05, 0, -0.1],
        "degrees_per_second": 90})");
inline const Json kWalking = Json::parse(R"({"type": "linear", "velocity": [0.3, 0, -0.2]})");
inline const Json kSwinging = Json::parse(
    R"({"type": "oscillation", "axis": [0, 0, 1], "amplitude": 0.1, "frequency": 1.5,
        "phase_degrees": 30})");

// The scene of followScene's JSON, named "follow.json" in its errors.
inline Scene parseFollowScene(const Json& j) {
    return parseScene(j.dump(), "follow.json");
}

}  // namespace cloth::test
