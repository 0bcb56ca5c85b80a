// Adaptive smoothed aggregation (Vaněk, Mandel & Brezina 1996; Brezina et al., "Adaptive smoothed
// aggregation (αSA)", SIAM J. Sci. Comput. 2004): the "aggregation" preconditioner of implicit
// Euler's conjugate gradient on the CPU (docs/integrators.md, "Preconditioners").
//
// Why: the geometric V-cycle's coarse space (bilinear P with a rotation term) cannot carry a
// curved stiff sheet's near-isometric motions, so its iteration count grows as the cloth hangs
// into folds (docs/performance.md, "What bounds the multigrid's iteration count"). Here the
// coarse space is built at every step from the system itself:
// - the near-null modes ("candidates"): the six rigid motions and k random vectors relaxed on
//   A e = 0 by one symmetric line sweep (what the sweeps cannot remove is what the coarse grid
//   must carry);
// - aggregates of 3 × 3 vertices, each one coarse vertex whose unknowns are the candidates'
//   coefficients on it (6 + k), orthonormalised aggregate by aggregate (P_t = Q, the coarse
//   candidates R);
// - P = (I − ω D⁻¹ A) P_t, smoothed once by block Jacobi (ω = 4 / (3 ρ(D⁻¹A))), which keeps a
//   5 × 5 coarse stencil;
// - Galerkin coarse grids A_c = Pᵀ A P, the same construction below with the coarse candidates
//   (the adaptive ones relaxed once more on the first coarse grid), the coarsest solved densely.
// The cycle is V(ν, ν) with alternating line Gauss–Seidel (cpu/block_grid.h), symmetric positive
// definite as the conjugate gradient needs. Everything is deterministic (a fixed random seed).
#pragma once

#include <cstdint>
#include <vector>

#include "cpu/block_grid.h"

namespace cloth {

class Aggregation {
public:
    struct Settings {
        int candidates = 8;              // adaptive candidates k beside the six rigid motions
        int sweeps = 2;                  // ν: line sweeps before and after the coarse correction
        int maxLevels = 4;               // grids, the fine one included
        std::size_t coarsestDofs = 400;  // a grid this small is solved densely
        bool smooth = true;              // P smoothed once (false: the tentative P, for tests)
        int candidateSweeps = 1;         // symmetric line sweeps that relax each adaptive candidate
        int coarseCandidateSweeps = 1;   // and again on every coarse grid that is coarsened
        bool carryCandidates = true;     // start from the last setup's candidates
    };
    static constexpr int kRigid = 6;
    static constexpr int kAggregate = 3;  // vertices an aggregate spans along each axis

    void setSettings(const Settings& s) { settings_ = s; }
    // Per step: the hierarchy under the fine system (b = 3, the vertices' velocity changes;
    // pinned vertices' unknowns fixed) at the vertices' positions x (3 a vertex).
    void setup(BlockGrid fine, const std::vector<double>& x);
    // z = V r on the fine grid (r = 0 on fixed unknowns; z is 0 there).
    void apply(const double* r, double* z);

    int levels() const { return int(levels_.size()); }
    const BlockGrid& grid(int l) const { return levels_[std::size_t(l)].a; }
    // For tests: level l's candidates (column c of dofs(l) values at c × dofs(l)), and its P
    // (to level l + 1) applied to a field of level l + 1 (fine = P coarse).
    const std::vector<double>& candidates(int l) const { return levels_[std::size_t(l)].b; }
    int candidateCount(int l) const { return levels_[std::size_t(l)].columns; }
    void prolong(int l, const double* coarse, double* fine) const;   // fine += P coarse
    void restrict(int l, const double* fine, double* coarse) const;  // coarse = Pᵀ fine

private:
    // One axis of an aggregation: index i of n lies in aggregate of[i] (3 consecutive indices,
    // the last aggregate 2–4).
    struct Axis {
        std::vector<int> of;
        int count = 0;
    };
    static Axis aggregate(int n);
    static constexpr int kReach = 9;  // P's blocks a vertex: the aggregates (−1…1)² around its own
    struct Level {
        BlockGrid a;
        LineSmoother smoother;
        DenseSolve dense;       // the coarsest only
        std::vector<double> b;  // the candidates, column-major
        int columns = 0;
        Axis u, v;  // this grid's aggregation into the next
        // P to this grid from the next: vertex k's block of aggregate offset s (kReach of them,
        // b × b_next, row-major) at (k kReach + s) b b_next.
        std::vector<double> p;
        std::vector<double> r, z, t;
    };
    void rigidCandidates(Level& fine, const std::vector<double>& x) const;
    void startCandidates(Level& top);
    void relaxCandidates(Level& level, int first, int sweeps) const;
    // The next grid from level l: P tentative and smoothed, the coarse candidates, Galerkin.
    void coarsen(int l);
    void tentative(Level& fine, Level& coarse) const;
    void smoothProlongation(Level& fine, int coarseB) const;
    void galerkin(const Level& fine, Level& coarse) const;
    template <int kB, int kC>  // fine and coarse block sizes (0: at run time)
    void galerkinSized(const Level& fine, Level& coarse) const;
    void cycle(int l);

    Settings settings_;
    std::vector<Level> levels_;
    std::vector<double> carried_;  // the fine grid's adaptive candidates of the last setup
};

}  // namespace cloth
