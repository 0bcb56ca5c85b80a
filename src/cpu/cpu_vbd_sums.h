// The sums of vbd's translation and its levels (cpu_vbd_translation.cpp, cpu_vbd_levels.cpp):
// a row's part of a 3 × 3 problem, kept in double. Included only by those two files.
#pragma once

#include "model/vbd_lane.h"

namespace cloth::vbd_sums {

inline constexpr int kSums = 10;                  // gradient (3), Hessian (6), Σ m/h²
inline constexpr int kMass = kSums - 1;           // the index of Σ m/h²
inline constexpr int kOwn = kSums + 1;            // and Σ (m/h² + m c/h): the levels' own sums
inline constexpr double kContactStiffness = 1e4;  // × m/h²: a contact's hold along its push

// Field by field: gathered into an array first, the lane's fields were stored 8 bytes at a time
// and loaded back 16 at a time, a store-forwarding stall on every call (a fifth of the levels'
// block sums at 256², perf).
inline void addLane(const VbdLane<double>& a, double* out) {
    out[0] += a.gx, out[1] += a.gy, out[2] += a.gz;
    out[3] += a.xx, out[4] += a.yy, out[5] += a.zz;
    out[6] += a.xy, out[7] += a.xz, out[8] += a.yz;
}

}  // namespace cloth::vbd_sums
