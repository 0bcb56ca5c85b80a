// Files a run writes (DESIGN.md §5). Each is written to a temporary name and renamed into place,
// so a failure never leaves a half-written file or clobbers the previous one; a state with a
// non-finite number is refused (nothing non-finite is ever written).
#pragma once

#include <string>

#include "model/output_file.h"
#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// Header i,j,x,y,z,vx,vy,vz; one row per vertex in index order; %.17g for double, %.9g for float
// (the digits that round-trip).
void writeCsv(const std::string& path, const SimState& state, Precision precision);

// Wavefront OBJ: v (positions), vt (u, v in [0, 1]), vn (DESIGN.md §2 normals), f (two triangles
// per grid cell, counter-clockwise about the normal); a 1-D chain as its segments, one `l` each.
void writeObj(const std::string& path, const SimState& state, const std::string& sceneName);

// Point cache PC2, the format of 3ds Max's Point Cache and Blender's Mesh Cache modifier:
// little-endian, a 32-byte header ("POINTCACHE2" and a NUL, int32 version 1, int32 points, float32
// start frame, float32 sample rate, int32 samples), then each sample's float32 x, y, z per vertex
// in index order k = j·nu + i, the order of writeObj's `v` lines. Start frame 0 and sample rate 1
// (frames per sample): sample s is frame s. The samples are written as the run makes them, to the
// temporary file OutputFile keeps; commit() puts the file in place once all of them are in, so a
// run that stops short (unstable, a failed write) leaves the previous file as it was.
class Pc2Writer {
public:
    // Opens `path` and writes the header; OutputError if it cannot, std::invalid_argument when
    // `points` or `samples` is not in [1, 2³¹ − 1].
    Pc2Writer(const std::string& path, long points, long samples);
    // One sample: the state's positions rounded to float32. Refuses a state with a non-finite
    // number, of another size, or past the header's count of samples.
    void add(const SimState& state);
    // OutputError when a write failed or fewer samples than the header counts were added.
    void commit();

private:
    std::string path_;
    OutputFile out_;
    long points_, samples_, added_ = 0;
};

}  // namespace cloth
