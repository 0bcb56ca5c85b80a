// An independent check of one cloth frame for self-intersection, sharing no code with src/ (no
// glm): the oracle the collision tests hold a simulated frame, read from its OBJ file, against.
// It counts mesh edges that pass through triangles and measures how close non-neighbouring
// parts of the surface come, both over a uniform grid of cells, so that a 128x128 frame takes
// tens of milliseconds where all pairs would take tens of seconds.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace ref {

struct TriangleMesh {
    std::vector<std::array<double, 3>> positions;
    std::vector<std::array<int, 3>> triangles;  // 0-based vertex indices
};

// Reads `v x y z` and `f ...` lines: face corners like `7`, `7/7`, `7//7`, `7/7/7`, 1-based, a
// negative index counting back from the last vertex read so far; a polygon of more than three
// corners is fanned from its first corner. Ignores vt, vn, l, comments and every other line.
// Throws std::runtime_error naming the file and line on a malformed v or f line (fewer than
// three numbers or corners, text that is not a number, a non-finite coordinate) or on an index
// outside the vertices read so far, and naming the file when it cannot be opened.
TriangleMesh readObj(const std::string& path);

// The number of (mesh edge, triangle) pairs that share no vertex and where the edge's segment
// passes through the triangle; each undirected edge (the triangles' sides, duplicates merged)
// counts once per triangle it crosses. Only proper crossings count: the segment's ends strictly
// on opposite sides of the triangle's plane and its line strictly inside the three sides. A
// segment that merely touches (an end on the plane, through a side or corner, or lying in the
// plane) is not counted, so a flat or exactly-stacked mesh reads 0; a crossing near (not on) a
// side shared by two triangles counts in exactly one of them (see the .cpp).
// Throws std::invalid_argument on a non-finite position or a triangle index out of range.
long countEdgeTriangleCrossings(const TriangleMesh& mesh);

struct Separation {
    double distance;   // +infinity when no pair qualified
    std::string pair;  // e.g. "vertex 12 - triangle 40", "edge 3-4 - edge 10-11"; "" if none
};

// The smallest distance over (vertex, triangle) and (edge, edge) pairs that are not topological
// neighbours: a pair is skipped when some vertex of one element is within `rings` edges (graph
// distance on the mesh's edge graph) of some vertex of the other, so rings = 0 skips only pairs
// that share a vertex. Only vertices used by some triangle take part. Pairs farther apart than
// `cutoff` are not looked at: the result is the true minimum when it is <= cutoff, else
// +infinity. Each element looks no further than the cutoff or the closest pair found so far.
// Edges passing through triangles need not bring any of these pairs close (two interlocked
// triangles keep their corners and sides apart), so check countEdgeTriangleCrossings too.
// Throws std::invalid_argument on rings < 0, a negative or NaN cutoff, a non-finite position or
// a triangle index out of range.
Separation minimumSeparation(const TriangleMesh& mesh, int rings, double cutoff);

}  // namespace ref
