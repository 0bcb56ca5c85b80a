// The sums of vbd's translation and its levels (cpu_vbd_translation.cpp, cpu_vbd_levels.cpp):
// a row's part of a 3 × 3 problem, kept in double. Included only by those two files.
#pragma once

#include "model/vbd_lane.h"

namespace cloth::vbd_sums {

inline constexpr int kSums = 10;                  // gradient (3), Hessian (6), Σ m/h²
inline constexpr int kMass = kSums - 1;           // the index of Σ m/h²
inline constexpr int kOwn = kSums + 1;            // and Σ (m/h² + m c/h): the levels' own sums
inline constexpr double kContactStiffness = 1e4;  // × m/h²: a contact's hold along its push

inline void addLane(const VbdLane<double>& a, double* out) {
    const double v[9] = {a.gx, a.gy, a.gz, a.xx, a.yy, a.zz, a.xy, a.xz, a.yz};
    for (int e = 0; e < 9; ++e) out[e] += v[e];
}

}  // namespace cloth::vbd_sums
