// A closed triangle mesh turned into a signed-distance grid, once, on the CPU (docs/colliders.md
// §4): exact unsigned distance to the triangles, sign by the generalised winding number, sampled
// on a regular grid that covers the mesh's bounds plus a band. model/collider_shapes.h samples it.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "model/collider_shapes.h"

namespace cloth {

struct TriMesh {
    std::vector<glm::dvec3> vertices;
    std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
};

// Where a mesh came from, for messages: the scene file and key (`colliders[2].file`); both may
// be empty (then the OBJ's own path is named).
struct MeshSource {
    std::string file, key;
};

// The most samples a grid may have (8 bytes each: 512 MiB).
inline constexpr std::int64_t kMaxSdfSamples = std::int64_t(1) << 26;

// Reads the OBJ's triangles (polygons are triangulated) through tinyobjloader and welds vertices
// with identical coordinates. InputError (naming `objPath` and the reason) when the file is
// missing or unreadable, has no triangle, or is not closed and manifold.
TriMesh loadObjMesh(const std::string& objPath, const MeshSource& source = {});

// The first reason the mesh is not a closed, consistently oriented 2-manifold, or nothing: every
// edge (a, b) of a triangle must appear in exactly one other triangle, as (b, a). Vertex numbers
// in the message are the OBJ's (1-based). A triangle with a repeated vertex is refused too.
std::optional<std::string> closedManifoldProblem(const TriMesh& mesh);

// Exact distance from p to the triangle (a, b, c) (closest point by Voronoi region).
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                             const glm::dvec3& c);

// The generalised winding number of a closed mesh about p: ±1 inside (the sign says the
// orientation), 0 outside; Σ solid angles / 4π (Van Oosterom–Strackee).
double windingNumber(const TriMesh& mesh, const glm::dvec3& p);

// Samples every cell size `cell` over the mesh's bounds grown by `band` on each side (and at
// least two samples per axis): φ = ±(distance to the nearest triangle), negative where
// |winding number| > ½. Rows of samples run on all cores; a triangle whose bounding sphere is
// farther than the best distance is skipped, and the winding number is evaluated only within
// one cell of the surface (farther samples take the sign of their row neighbour, which no
// surface separates from them). InputError when cell ≤ 0, band < 0 or the grid would exceed
// kMaxSdfSamples.
SdfGrid bakeSdf(const TriMesh& mesh, double cell, double band, const MeshSource& source = {});

// A mesh collider as the scene holds it: the closed mesh (drawn, exported) and its baked grid
// (sampled by the contact response).
struct BakedMesh {
    TriMesh mesh;
    SdfGrid grid;
};

}  // namespace cloth
