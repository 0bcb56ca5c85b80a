// Checks for the collider keys of docs/colliders.md §5 (box, capsule, mesh, thickness, friction,
// motion), ready for the scene loader: each returns the validated value or throws InputError
// naming the scene file and the key path (`colliders[2].radius`), so bad input exits with 2.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "model/collider_motion.h"
#include "model/mesh_sdf.h"

namespace cloth {

// Where a value sits: the scene file and the key path of the value.
struct KeyRef {
    std::string file, key;
};

glm::dvec3 checkFinite(const KeyRef& at, const glm::dvec3& v);          // every component finite
double checkRadius(const KeyRef& at, double radius);                    // finite, > 0 [m]
glm::dvec3 checkHalfExtents(const KeyRef& at, const glm::dvec3& half);  // each finite, > 0 [m]
double checkThickness(const KeyRef& at, double thickness);              // finite, ≥ 0 [m]
double checkFriction(const KeyRef& at, double friction);                // finite, ≥ 0

// A unit axis from a finite, non-zero vector (|axis| > 1e-12); `at` is the axis' own key.
glm::dvec3 checkAxis(const KeyRef& at, const glm::dvec3& axis);

// {"axis": [x, y, z], "degrees": a} (`at` names the rotation object; messages name its
// `.axis` or `.degrees`): the rotation matrix, local → world.
glm::dmat3 checkRotation(const KeyRef& at, const glm::dvec3& axis, double degrees);

// The mesh file of a `mesh` collider, relative to the scene file's folder unless absolute:
// read, checked closed and manifold, and baked with grid cell `cell` and `band` (`at` names
// the collider; messages name its `.file`, `.cell` or `.band`). The thickness must stay inside
// the band, where the grid is exact to its interpolation error.
// The mesh comes back with its grid (model/mesh_sdf.h), for the renderer and the export to draw.
BakedMesh checkMeshCollider(const KeyRef& at, const std::string& objFile, double cell, double band,
                            double thickness);

// A motion's numbers: axis non-zero, frequency ≥ 0, everything finite (`at` names the motion
// object; messages name its member keys, as docs/colliders.md §5 spells them).
Motion checkMotion(const KeyRef& at, const Motion& motion);

}  // namespace cloth
