// How fast a moving collider's surface can go (docs/colliders.md §3, §7): with the largest step a
// collider may take through the cloth (maxColliderStepTravel), a scene is safe from tunnelling
// when maxMotionSpeed(c)·Δt stays below it.
#pragma once

#include <glm/glm.hpp>

#include "model/scene.h"

namespace cloth {

// A sphere containing the collider's surface at rest (its pose at t = 0 before the motion):
// exact for a sphere, |h| about the centre for a box, the segment's midpoint and half length + r
// for a capsule, the centre of the posed OBJ vertices' bounds and the farthest vertex for a mesh.
// A plane is unbounded: radius +∞.
struct BoundingSphere {
    glm::dvec3 center{0};
    double radius = 0;  // [m]
};
BoundingSphere boundingSphere(const Collider& c);

// The largest speed of any point of the collider's surface under its motion [m/s]: 0 without
// one; linear |v|; oscillation 2π f |A| (its peak, at the centre of the swing); rotation ω times
// the largest distance of the surface from the axis, bounded by the bounding sphere's (the
// distance of its centre from the axis plus its radius; exact for a sphere and a capsule whose
// axis crosses the rotation axis at right angles, an upper bound otherwise). A rotating plane
// has points arbitrarily far from the axis: +∞ (0 if ω = 0).
double maxMotionSpeed(const Collider& c);

}  // namespace cloth
