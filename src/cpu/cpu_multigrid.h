// The geometric multigrid preconditioner of implicit Euler's conjugate gradient on the CPU
// (docs/integrators.md, "Preconditioners"): one symmetric V-cycle over the grid and its
// coarsenings.
//
// A coarse grid keeps every other vertex (the last one always: coarse I sits on fine
// min(2I, n − 1)); bilinear interpolation P carries coarse corrections to the grid above and
// its transpose R = Pᵀ restricts residuals. Every grid's system is a 5×5 stencil of 3×3
// symmetric blocks per vertex: the fine one is assembled from the system's terms (springs' J_s
// and damping, the bending weights, mass, drag, grab), a coarse one is
// the Galerkin product A_c = Pᵀ A P of the grid above (bilinear P keeps radius 2). Pins are
// constraints on every grid: a coarse vertex is pinned iff the fine vertex it sits on is, its
// rows and columns are the identity's, restriction gives 0 there and prolongation skips pinned
// fine vertices. Smoothing is alternating-line block Gauss–Seidel: every row, then every column,
// solved exactly (banded Cholesky) against the current values of the rest, the lines in 5
// colours (j mod 5, i mod 5) so that lines of a colour do not touch; the membrane's springs are
// stiff along u and v and soft in shear, an anisotropy point smoothers cannot handle. It
// converges for any symmetric positive definite A; after the coarse correction it runs in the
// exact reverse order (columns, then rows, colours backwards), its adjoint. The coarsest grid
// is solved by a dense Cholesky factorisation. The cycle is then a symmetric
// positive definite operator, as the conjugate gradient needs. It has no reductions: its result
// does not depend on the thread count.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "cpu/block_grid.h"
#include "cpu/cpu_soa.h"
#include "cpu/spin_barrier.h"
#include "model/grid.h"
#include "model/implicit_system.h"
#include "model/multigrid_levels.h"

namespace cloth {

// The threads that run a V-cycle together: thread `index` of `count`, a barrier between passes.
struct CycleThreads {
    int index = 0, count = 1;
    SpinBarrier* barrier = nullptr;
    void sync() const {
        if (barrier) barrier->arrive_and_wait();
    }
};

template <typename T>
class CpuMultigrid {
public:
    using FineSystem = ImplicitSystem<T, Soa3<T>>;
    // The cycle's arithmetic, in float too: a stiff membrane's A = m I + h²K holds m at 1e-6 of
    // h²K, under float's rounding of the Galerkin sums (its coarse grids went indefinite).
    using S = double;
    // A block of a stencil or of P: full 3×3 (P's rotation term makes coarse blocks asymmetric).
    using Block = glm::mat<3, 3, S, glm::defaultp>;

    // The hierarchy under an nu × nv grid: coarse grids down to at most kCoarsest vertices, for
    // a team of `threads` (any team gets the same result; this one gets the best balance). With
    // fineOnly, the fine grid's stencil alone, for the aggregation multigrid (fineGrid); apply
    // is then not to be called.
    void configure(int nu, int nv, int threads = 1, bool fineOnly = false);
    int levels() const { return int(levels_.size()); }  // the fine grid included
    bool configured() const { return configured_; }

    // Per step, once the fine system is linearised: the stencils of every grid, the smoothers'
    // inverted blocks and the coarsest factorisation. Every thread calls it; it ends with a sync.
    void linearise(const FineSystem& fine, const CycleThreads& threads);

    // z = V r on the fine grid (r = 0 on pinned rows; z is 0 there). Every thread calls it; it
    // ends with a sync.
    void apply(const std::vector<Vec3<T>>& r, std::vector<Vec3<T>>& z, const CycleThreads& threads);

    // For tests: the positions of grid l's vertices (as of the last linearise), and P applied to
    // a field of grid l (l ≥ 1) on every vertex of grid l − 1.
    const std::vector<Vec3<S>>& positions(int l) const { return levels_[std::size_t(l)].x; }
    std::vector<Vec3<S>> interpolate(int l, const std::vector<Vec3<S>>& coarse) const;
    // The fine grid's stencil (as of the last linearise) as a block grid of 3 unknowns a vertex,
    // pinned vertices' unknowns fixed: the fine grid of the aggregation multigrid.
    void fineGrid(BlockGrid& out) const;
    // For tests: grid l's stencil applied to a field of grid l (the rows of pinned vertices too).
    std::vector<Vec3<S>> stencilTimes(int l, const std::vector<Vec3<S>>& w) const;

    static constexpr int kCoarsest = kMultigridCoarsest;  // vertices of the grid solved exactly
    // Grids smaller than this run on one thread. Sharing every grid down to 10 × 10 is 13–29 %
    // faster than from 1024 vertices on the cotton drape at 38²–64² (docs/performance.md, "The
    // passes' barrier").
    static constexpr int kSerialBelow = 100;
    static constexpr int kSweeps = 1;    // smoothing sweeps before and after
    static constexpr int kStencil = 25;  // blocks per vertex: offsets (−2..2)²
    // A contact in the solve fixes its vertex's normal velocity (model/solve_contact.h). The
    // V-cycle keeps the fine grid's symmetric blocks and sees the constraint as a normal spring
    // this many times the vertex's mean diagonal: coarse corrections then move the cloth along
    // its contacts rather than into them, where the filter S would throw their work away.
    static constexpr double kContactPenalty = 1e1;

private:
    static constexpr int kBand = 8;  // a line's half bandwidth in unknowns: 3 × 2 + 2
    // One axis of a coarsening: coarse index I sits on fine index at[I]; fine index i lies in
    // cell lower[i] (between coarse lower[i] and lower[i] + 1) and takes (1 − w) of the one and
    // w of the other; cell C holds fine indices [first[C], first[C + 1]). A fine index on a
    // coarse one belongs to the cell below it (but 0 to cell 0), so that P keeps radius 2.
    struct Axis {
        std::vector<int> at, lower, first;
        std::vector<S> weight;
        int cells() const { return int(first.size()) - 1; }
    };
    // Every slot in its own place, in slot order: a coarse grid's records.
    static constexpr std::array<std::int8_t, kStencil> slotOrder() {
        std::array<std::int8_t, kStencil> order{};
        for (int slot = 0; slot < kStencil; ++slot) order[std::size_t(slot)] = std::int8_t(slot);
        return order;
    }
    // One direction's lines of a grid, in pairs: each thread's lines of colour c (line mod 5)
    // two at a time in order, pair p's two factors interleaved value by value, so that one
    // vector instruction steps both lines' substitutions (docs/performance.md, "The line solves
    // in pairs"). Lines of one colour lie out of each other's stencils: relaxing them together
    // gives what relaxing them one by one does. The threads split the lines as whole ranges, as
    // they split the rows, so that each gets as many lines of a colour as the others.
    static constexpr int kLanes = 2;
    struct Lines {
        int count = 0, length = 0, team = 1;  // lines, vertices a line, threads
        // Colour c's pairs of thread t: [start[c team + t], start[c team + t + 1]).
        std::vector<int> start;
        std::vector<int> pairLines;  // pair p's lines: lanes 2p and 2p + 1 (−1: none)
        // Pair p's factors: lane l's entry e of row i at ((p dofs + i) width + e) kLanes + l.
        std::vector<double> factor;
        void configure(int lineCount, int lineLength, int teamSize) {
            count = lineCount;
            length = lineLength;
            team = teamSize;
            start.assign(1, 0);
            pairLines.clear();
            for (int c = 0; c < 5; ++c)
                for (int t = 0; t < team; ++t) {
                    const int first = int(std::int64_t(count) * t / team);
                    const int last = int(std::int64_t(count) * (t + 1) / team);
                    int lane = 0;
                    for (int line = first + ((c - first) % 5 + 5) % 5; line < last; line += 5) {
                        pairLines.push_back(line);
                        lane = (lane + 1) % kLanes;
                    }
                    if (lane != 0) pairLines.push_back(-1);
                    start.push_back(int(pairLines.size()) / kLanes);
                }
            factor.assign(pairLines.size() / kLanes * values(), 0.0);
        }
        std::size_t dofs() const { return 3 * std::size_t(length); }
        std::size_t values() const { return dofs() * (kBand + 1) * kLanes; }  // a pair's
        int line(int p, int lane) const { return pairLines[std::size_t(kLanes * p + lane)]; }
        // The pairs of colour c that a thread relaxes: its own lines' with the team of
        // configure, a share of them all with another.
        std::pair<int, int> pairs(int c, const CycleThreads& threads) const {
            const int* s = &start[std::size_t(c * team)];
            if (threads.count == team) return {s[threads.index], s[threads.index + 1]};
            const int n = s[team] - s[0];
            return {s[0] + int(std::int64_t(n) * threads.index / threads.count),
                    s[0] + int(std::int64_t(n) * (threads.index + 1) / threads.count)};
        }
        double* pair(int p) { return &factor[std::size_t(p) * values()]; }
        const double* pair(int p) const { return &factor[std::size_t(p) * values()]; }
    };
    struct Level {
        int nu = 0, nv = 0;
        Axis u, v;  // from the grid above (unused on the fine grid)
        // A vertex's stencil: the block of offset (di, dj), slot 5(dj+2)+di+2, lies at place[slot]
        // in the vertex's record of perVertex blocks, or nowhere (place −1: the block is 0).
        // A coarse grid's Galerkin product reaches all 25 offsets, full blocks in slot order.
        // The fine grid's springs and bending reach 13 (kFinePlaces), symmetric blocks: half the
        // memory traffic of the sweeps, whose loads bound them.
        std::vector<Sym3<S>> symmetric;
        std::vector<Block> a;
        std::array<std::int8_t, kStencil> place = slotOrder();
        int perVertex = kStencil;
        bool reaches(int slot) const { return place[std::size_t(slot)] >= 0; }
        std::size_t at(std::int64_t k, int slot) const {
            return std::size_t(k * perVertex + place[std::size_t(slot)]);
        }
        Block block(std::int64_t k, int slot) const {
            if (!reaches(slot)) return Block(0);
            return symmetric.empty() ? a[at(k, slot)] : symmetric[at(k, slot)].matrix();
        }
        // Asks the cache for a block ahead of its use (a column's vertices lie a row apart).
        void prefetch(std::int64_t k, int slot) const {
            const char* start = symmetric.empty()
                                    ? reinterpret_cast<const char*>(&a[at(k, slot)])
                                    : reinterpret_cast<const char*>(&symmetric[at(k, slot)]);
            const std::size_t bytes = symmetric.empty() ? sizeof(Block) : sizeof(Sym3<S>);
            __builtin_prefetch(start);
            __builtin_prefetch(start + bytes - 1);
        }
        // Block (k, slot) times w, for a slot that reaches.
        Vec3<S> times(std::int64_t k, int slot, const Vec3<S>& w) const {
            return symmetric.empty() ? a[at(k, slot)] * w : symmetric[at(k, slot)] * w;
        }
        // The slots that reach, in slot order, with their place in a record and their
        // neighbour's index offset: every one (kAll), those off the row (kOffRow: what a row's
        // sweep gathers), those off the column (kOffColumn). For vertices two or more from every
        // side, whose loops then need no bounds.
        struct Reach {
            int place;
            std::int64_t offset;
        };
        static constexpr int kOffRow = 0, kOffColumn = 1, kAll = 2;
        std::vector<Reach> interior[3];
        bool isInterior(int i, int j) const { return i >= 2 && j >= 2 && i < nu - 2 && j < nv - 2; }
        // sum −= Σ block × w over `which` of interior vertex k, in slot order.
        void subtract(Vec3<S>& sum, std::int64_t k, int which, const Vec3<S>* w) const {
            if (symmetric.empty()) {
                const Block* record = &a[std::size_t(k * perVertex)];
                for (const Reach& e : interior[which]) sum -= record[e.place] * w[k + e.offset];
            } else {
                const Sym3<S>* record = &symmetric[std::size_t(k * perVertex)];
                for (const Reach& e : interior[which]) sum -= record[e.place] * w[k + e.offset];
            }
        }
        std::vector<Vec3<S>> x;  // the vertices' positions (a coarse one: its fine vertex's)
        // P from this grid to the one above (unused on the fine grid): 4 blocks per vertex of
        // the grid above, one per corner of the coarse cell it lies in (see prolongation).
        std::vector<Block> p;
        // The smoother's factors: every row (direction 0) and column (1) of the grid as one
        // banded system (3 unknowns a vertex, the stencil's blocks along it), A_line = L Lᵀ,
        // L's band stored row by row, kBand + 1 entries (the diagonal last, as its reciprocal).
        Lines lines[2];
        std::vector<std::uint8_t> pinned;
        std::vector<Vec3<S>> r, z, t;  // the fine grid's r, z: copies of the caller's
        std::int64_t count() const { return std::int64_t(nu) * nv; }
    };

    static Axis coarsen(int n);
    static constexpr int stencilSlot(int di, int dj) { return 5 * (dj + 2) + di + 2; }
    // The fine grid's offsets in the order of its records: those across a row (what a row's
    // sweep reads), the diagonals, those along a row (what a column's sweep reads with the
    // diagonals), the vertex itself. The springs of the 12-neighbour stencil reach no others.
    static constexpr int kFineBlocks = 13;  // blocks a fine vertex stores
    static constexpr int kFinePlaces[kFineBlocks][2] = {{0, -2}, {0, -1}, {0, 1}, {0, 2},  {-1, -1},
                                                        {1, -1}, {-1, 1}, {1, 1}, {-2, 0}, {-1, 0},
                                                        {1, 0},  {2, 0},  {0, 0}};
    // The offsets the bending stencil reaches: second differences along u and v, the twists of
    // the four cells around the vertex.
    static constexpr int kBendReach[13][2] = {{0, 0},  {-1, 0}, {1, 0},  {-2, 0}, {2, 0},
                                              {0, -1}, {0, 1},  {0, -2}, {0, 2},  {-1, -1},
                                              {1, -1}, {-1, 1}, {1, 1}};
    static constexpr bool isFinePlace(int di, int dj) {
        for (const auto& o : kFinePlaces)
            if (o[0] == di && o[1] == dj) return true;
        return false;
    }
    // Every offset the fine assembly writes (the springs of kSpringOffsets, the bending) has a
    // place in the fine records.
    // The places are the 13 offsets with |di| + |dj| ≤ 2, each once: the set the GPU's
    // stencilReaches (shaders/compute/multigrid.glsl) keeps.
    static constexpr bool placesAreTheDiamond() {
        for (int e = 0; e < kFineBlocks; ++e) {
            const int di = kFinePlaces[e][0], dj = kFinePlaces[e][1];
            if ((di < 0 ? -di : di) + (dj < 0 ? -dj : dj) > 2) return false;
            for (int f = 0; f < e; ++f)
                if (kFinePlaces[f][0] == di && kFinePlaces[f][1] == dj) return false;
        }
        return true;
    }
    static constexpr bool stencilIsPlaced() {
        for (const auto& o : kBendReach)
            if (!isFinePlace(o[0], o[1])) return false;
        for (const SpringOffset& o : kSpringOffsets)
            if (!isFinePlace(o.di, o.dj)) return false;
        return true;
    }
    // The cells of an axis that have coarse index I as a corner: I − 1 and I, where they exist.
    template <typename Fn>
    static void forEachCellOf(const Axis& axis, int I, const Fn& fn) {
        for (int C = std::max(0, I - 1); C <= std::min(I, axis.cells() - 1); ++C) fn(C);
    }
    using FineSystemS = ImplicitSystem<S, Soa3<S>>;  // the fine system in the cycle's arithmetic
    void assembleFine(const FineSystemS& fine, const CycleThreads& threads);
    void galerkin(int l, const CycleThreads& threads);      // level l from level l − 1
    void prolongation(int l, const CycleThreads& threads);  // level l's P, from its positions
    Vec3<S> prolongAt(int l, std::int64_t k, const Vec3<S>* coarse) const;  // (P z_c)_k
    void smoother(int l, const CycleThreads& threads);
    // Line `line`'s right-hand side into lane `lane` of y (interleaved as a pair's factor).
    static void lineRightHandSide(const Level& g, int direction, int line, const Vec3<S>* r,
                                  const Vec3<S>* z, double* y, int lane);
    // Pairs [first, last) of one colour relaxed, two pairs at a time.
    void relaxPairs(Level& g, int direction, int first, int last, const Vec3<S>* r, Vec3<S>* z);
    static constexpr int kAhead = 4;  // vertices ahead along a line whose blocks are prefetched
    void cycle(int l, const Vec3<S>* r, Vec3<S>* z, const CycleThreads& threads);
    void factorCoarsest();
    void solveCoarsest();
    // [begin, end) of a grid's vertices for this thread (whole rows).
    static std::pair<std::int64_t, std::int64_t> slice(int nu, int nv, const CycleThreads& threads);

    bool configured_ = false, fineOnly_ = false;
    std::vector<Level> levels_;
    // The fine system's data in double (float's rounding of h²K's blocks at 1e6 N/m, 128², is
    // larger than the mass: a float stencil was indefinite).
    Soa3<S> x_;
    std::vector<StencilSpring<S>> springs_;
    std::vector<S> inverseMass_;
    // The Galerkin product's first half, (A P)_kQ for every fine vertex k of the grid above and
    // the 4 × 4 coarse vertices Q around its cell: slot (Q − cell + 1) along u, + 4 × that along v.
    std::vector<Block> product_;
    std::vector<double> cholesky_;  // the coarsest system's factor L (row-major, lower)
    std::vector<double> solve_;
};

extern template class CpuMultigrid<float>;
extern template class CpuMultigrid<double>;

}  // namespace cloth
