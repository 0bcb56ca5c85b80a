// The grids of implicit Euler's multigrid preconditioner (docs/integrators.md, "Preconditioners"),
// the same on both backends (cpu/cpu_multigrid.h, gpu/gpu_multigrid.h): the cloth's nu × nv grid,
// then each coarsening keeps every other vertex along both axes (coarse I sits on fine
// min(2I, n − 1), so the last vertex always stays), down to a grid of at most
// kMultigridCoarsest vertices, which is solved exactly.
#pragma once

#include <cstdint>
#include <vector>

namespace cloth {

inline constexpr int kMultigridCoarsest = 64;
// The GPU's line solves: at most this many chunks a line, one invocation each
// (shaders/compute/multigrid.glsl chunkVertices).
inline constexpr int kMultigridChunks = 32;

// Vertices along an axis of n after one coarsening: an axis of 1 or 2 stays.
constexpr int coarsenedCount(int n) {
    return n <= 2 ? n : n / 2 + 1;
}

struct MultigridLevel {
    int nu = 0, nv = 0;
    std::int64_t count() const { return std::int64_t(nu) * nv; }
};

// Fine grid first, the coarsest last; stops early where neither axis shrinks.
inline std::vector<MultigridLevel> multigridLevels(int nu, int nv) {
    std::vector<MultigridLevel> levels{{nu, nv}};
    while (levels.back().count() > kMultigridCoarsest) {
        const MultigridLevel& above = levels.back();
        const MultigridLevel next{coarsenedCount(above.nu), coarsenedCount(above.nv)};
        if (next.nu == above.nu && next.nv == above.nv) break;
        levels.push_back(next);
    }
    return levels;
}

}  // namespace cloth
