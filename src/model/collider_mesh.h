// Triangle meshes of the colliders, built on the CPU without GL, shared by the OBJ export and
// (after the wiring step) the renderer. Every closed shape comes out welded, closed, manifold
// and counter-clockwise seen from outside, so it can also be fed back as a `mesh` collider.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "model/collider_shapes.h"
#include "model/mesh_sdf.h"
#include "model/scene.h"

namespace cloth {

// A square of side 2·halfSize on the plane, centred on its point, facing along its normal
// (two triangles; the only open shape).
TriMesh planeQuad(const PlaneT<double>& plane, double halfSize);
// An icosphere: the icosahedron split `subdivisions` times (20·4^s triangles), on the sphere.
TriMesh sphereMesh(const SphereT<double>& sphere, int subdivisions);
TriMesh boxMesh(const BoxT<double>& box);  // 8 vertices, 12 triangles
// Two hemispheres joined by a cylinder: `slices` around the axis, `stacks` per hemisphere.
TriMesh capsuleMesh(const CapsuleT<double>& capsule, int slices, int stacks);

// The scene's colliders as meshes (plane quads of half size `planeHalfSize`), named
// "collider<k>_<type>".
std::vector<std::pair<std::string, TriMesh>> colliderMeshes(const std::vector<Collider>& colliders,
                                                            double planeHalfSize);

// Writes meshes as one Wavefront OBJ, an `o` group each, with per-vertex normals (area-weighted
// face normals). Written through model/output_file.h, and finite, like solver/output.h's files.
void writeMeshesObj(const std::string& path,
                    const std::vector<std::pair<std::string, TriMesh>>& meshes);

}  // namespace cloth
