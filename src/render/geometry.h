// Geometry the renderer draws, built on the CPU without GL (so tests can check it): the cloth's
// index buffer, the packed vec4 vertex data the CPU backend uploads, and the colliders' lit
// triangles.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "model/mesh_sdf.h"
#include "solver/solver.h"

namespace cloth::render {

// Two triangles per grid cell, counter-clockwise about the normal of DESIGN.md §2 (û × v̂
// direction), so gl_FrontFacing is the normal's side. A 1-D chain (nu or nv = 1) is a line
// strip through its vertices in index order instead.
struct ClothIndices {
    bool lines = false;
    std::vector<std::uint32_t> indices;
};
ClothIndices clothIndices(int nu, int nv);

// One vec4 per vertex in the GPU layout (DESIGN.md §3, 16-byte stride): positions with w = 1
// and the unit normals of DESIGN.md §2 (0 where undefined). Returns false (and leaves the
// output unspecified) if any coordinate is not finite: such a state is never drawn.
bool packCloth(const SimState& state, std::vector<glm::vec4>& positions,
               std::vector<glm::vec4>& normals);

// A collider's triangle mesh (model/collider_mesh.h) as the renderer draws it: three vertices per
// triangle, each lit by the area-weighted mean normal of the faces around that vertex that meet
// the triangle at less than `creaseDegrees` (smooth across a sphere's facets, sharp at a box's
// edges).
struct LitMesh {
    std::vector<glm::vec3> positions, normals;  // one per triangle corner
};
LitMesh litMesh(const TriMesh& mesh, double creaseDegrees = 40);

}  // namespace cloth::render
