// Whether a scene's cloth fits float arithmetic (the GPU backend, and the CPU backend in float):
// the springs and colliders take squares of lengths (|d|², |p − c|²), finite in float below
// √FLT_MAX ≈ 1.8e19 m. A cloth that reaches past 1e18 m from the world's origin, or spans as
// much, is an input error naming its key, where it would otherwise go non-finite at its first
// step and be reported unstable.
#pragma once

#include <algorithm>
#include <cstdio>

#include "model/errors.h"
#include "model/scene.h"

namespace cloth {

inline constexpr double kFloatReach = 1e18;  // [m]

// InputError (cloth.size or cloth.origin) for a cloth beyond kFloatReach.
inline void checkFloatRange(const Scene& scene) {
    const Grid g = scene.grid();
    double reach = 0;
    for (int i : {0, g.nu - 1})
        for (int j : {0, g.nv - 1}) reach = std::max(reach, glm::length(g.restPosition(i, j)));
    const double extent = g.extent();
    if (reach < kFloatReach && extent < kFloatReach) return;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "the cloth %s %.3g m, past the %.0e m that float arithmetic can square; use "
                  "double precision on the CPU (--precision double) or a smaller scene",
                  extent >= kFloatReach ? "spans" : "reaches", std::max(extent, reach),
                  kFloatReach);
    throw InputError(scene.source, extent >= kFloatReach ? "cloth.size" : "cloth.origin", buf);
}

}  // namespace cloth
