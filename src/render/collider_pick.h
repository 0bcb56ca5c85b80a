// Which collider the cursor's ray meets first (the viewer's collider drag, docs/viewer.md): the
// colliders posed at the solver's time with their drags (model/collider_pose.h), each marched
// along the ray by its signed distance (sphere tracing: exact for the analytic shapes, which are
// true distances; a mesh's trilinear grid, whose slope can reach √3, is marched inside its grid's
// box with steps of φ/√3). Planes are not picked: the ground fills the view, and a drag on it
// would hide the pan gesture. No GL.
#pragma once

#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "model/collider_pose.h"
#include "model/scene.h"
#include "render/camera.h"

namespace cloth::render {

struct ColliderHit {
    std::size_t index = 0;  // in the colliders given
    glm::dvec3 point{0};    // on the surface φ = 0 [m]
    double distance = 0;    // from the ray's origin [m]
};

std::optional<ColliderHit> pickCollider(const Ray& ray, const std::vector<Collider>& colliders,
                                        double time, const std::vector<ColliderDrag>& drags,
                                        double maxDistance = 1e3);

// The offset a drag asks for: the one it started from, moved by where the ray now meets the
// camera-facing plane through the picked point (normal: the view direction when it started),
// less the picked point. nullopt when the ray misses that plane.
std::optional<glm::dvec3> dragTarget(const Ray& ray, const glm::dvec3& pickedPoint,
                                     const glm::dvec3& planeNormal, const glm::dvec3& startOffset);

}  // namespace cloth::render
