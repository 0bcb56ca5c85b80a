// The colliders of docs/colliders.md, written from that page alone and sharing no code with
// src/: the oracle for model/collider_shapes.h and model/collider_contact.h. Plain loops over the
// six faces, the clamped segment parameter and the eight grid corners, no glm.
#pragma once

#include <array>
#include <vector>

#include "reference/reference.h"

namespace ref {

struct Contact {
    double phi;  // signed distance [m], negative inside
    V3 normal;   // outward unit normal
};

// Rotation of `degrees` about `axis` (normalised here), Rodrigues' vector formula.
V3 rotate(const V3& axis, double degrees, const V3& v);

// DESIGN.md §2's two shapes as (φ, n): the plane's normal normalised here; the sphere's n is
// (0, 1, 0) at its very centre.
Contact planeContact(const Plane& plane, const V3& p);
Contact sphereContact(const Sphere& sphere, const V3& p);

Contact boxContact(const Box& box, const V3& p);

Contact capsuleContact(const Capsule& c, const V3& p);

// Trilinear value and the gradient of the trilinear interpolant, for a point inside the grid.
Contact gridContact(const Grid& g, const V3& p);

// Distance from p to the triangle abc: to its plane when the foot lies inside, else to the
// nearest of its three edges (each a clamped segment).
double triangleDistance(const V3& p, const V3& a, const V3& b, const V3& c);

// A collider of docs/colliders.md at time t (its motion applied, §3) on one vertex: the shape's
// contact evaluated in its rest frame (p moved back by the inverse motion, the normal turned
// forward), then respond() with the collider's velocity at p. The grid is posed by gridAxis,
// gridDegrees and gridTranslation; outside it φ = φ(clamped point) + the distance to it.
void collideMoving(const Collider& c, double t, V3& p, V3& v);

// docs/colliders.md §3: where the point x0 of a collider at rest is at time t under motion m,
// and the velocity of the point p moving with the collider at time t.
V3 motionPoint(const Motion& m, double t, const V3& x0);
V3 motionVelocity(const Motion& m, double t, const V3& p);

// docs/colliders.md §2: returns whether the vertex was in contact (φ < h) and updates p, v.
bool respond(const Contact& c, double thickness, double friction, const V3& vc, V3& p, V3& v);

}  // namespace ref
