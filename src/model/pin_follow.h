// Pins that follow a moving collider (docs/colliders.md §5): `{"at": [i, j], "follow": n}` holds
// vertex (i, j) at the pose of colliders[n] at time t applied to the vertex's grid position,
// x(t) = R(t)·x₀ + T(t), with the collider's velocity there, v_c(x(t)) (model/collider_motion.h).
// So a cape pinned at the shoulders of a turning figure turns with it.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "model/collider_motion.h"
#include "model/scene.h"

namespace cloth {

struct FollowPin {
    std::int64_t vertex;  // k = j·nu + i
    int collider;         // index in Scene::colliders
    Motion motion;        // that collider's
    glm::dvec3 rest;      // the vertex's grid position (DESIGN.md §2) [m]
};

struct PinState {
    glm::dvec3 position, velocity;  // [m], [m/s]
};

// Whether the pin follows a collider: its `follow` names one of the scene's colliders, and that
// one has a motion. A loaded scene's always do (checkFollowPins); in a scene edited in code one
// that does not is held still, never read out of range.
bool follows(const Scene& scene, const Pin& pin);

// The scene's follow pins, in the order the scene lists them.
std::vector<FollowPin> followPins(const Scene& scene);

// The scene with only the colliders whose `keep` is true (missing entries: kept), the follow
// indices renumbered to match; a pin that followed a dropped collider becomes a still pin. For
// callers that switch colliders off (the viewer's collider toggles).
Scene keepColliders(const Scene& scene, const std::vector<bool>& keep);

// Where a follow pin holds its vertex at time t [s], and with what velocity.
inline PinState followPinAt(const FollowPin& f, double t) {
    const glm::dvec3 p = poseAt(f.motion, t).apply(f.rest);
    return {p, velocityAt(f.motion, t).at(p)};
}

// The loader's check: every `follow` names a collider of the scene that has a motion; else an
// InputError naming `pins[k].follow`.
void checkFollowPins(const Scene& scene);

}  // namespace cloth
