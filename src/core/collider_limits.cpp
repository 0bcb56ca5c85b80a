#include "core/collider_limits.h"

#include <algorithm>
#include <limits>

#include "core/collider_validate.h"

namespace cloth {

double maxColliderStepTravel(const Collider& c) {
    const double h = c.thickness;
    if (c.as<Plane>() != nullptr) return std::numeric_limits<double>::infinity();
    if (const Sphere* s = c.as<Sphere>()) return s->radius + h;
    if (const Capsule* cap = c.as<Capsule>()) return cap->radius + h;
    if (const Box* b = c.as<Box>())
        return std::min({b->halfExtents.x, b->halfExtents.y, b->halfExtents.z}) + h;
    // The OBJ's own bounds (its frame; the grid around them is a band wider on every side).
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
    for (const glm::dvec3& v : std::get<MeshCollider>(c.shape).baked->mesh.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const glm::dvec3 extent = glm::max(hi - lo, glm::dvec3(0));
    return 0.5 * std::min({extent.x, extent.y, extent.z}) + h;
}

}  // namespace cloth
