// Files a run writes (DESIGN.md §5). Each is written to a temporary name and renamed into place,
// so a failure never leaves a half-written file or clobbers the previous one; a state with a
// non-finite number is refused (nothing non-finite is ever written).
#pragma once

#include <string>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// Header i,j,x,y,z,vx,vy,vz; one row per vertex in index order; %.17g for double, %.9g for float
// (the digits that round-trip).
void writeCsv(const std::string& path, const SimState& state, Precision precision);

// Wavefront OBJ: v (positions), vt (u, v in [0, 1]), vn (DESIGN.md §2 normals), f (two triangles
// per grid cell, counter-clockwise about the normal); a 1-D chain is written as one line `l`.
void writeObj(const std::string& path, const SimState& state, const std::string& sceneName);

}  // namespace cloth
