// A linear system on a regular grid with b unknowns a vertex and a 5 × 5 stencil of b × b
// blocks, the shape of every grid of the aggregation multigrid (cpu/cpu_aggregation.h): the
// fine grid (b = 3, a vertex's velocity change) and the coarse grids, whose unknowns are the
// coefficients of an aggregate's near-null modes. With it, the grid's smoother (alternating line
// Gauss–Seidel) and the dense factor of the coarsest grid. Everything in double: the stiff
// membrane's m I + h²K holds m at 1e-7 of h²K (cpu/cpu_multigrid.h).
#pragma once

#include <cstdint>
#include <vector>

namespace cloth {

struct BlockGrid {
    int nu = 0, nv = 0, b = 0;
    // Block (k, slot) of vertex k, slot 5 (dj + 2) + di + 2 for the neighbour (i + di, j + dj),
    // column-major at ((k 25 + slot) b + column) b + row (cpu/block_kernels.h). A fixed unknown's
    // row and column are the identity's (a pinned vertex, a coarse unknown whose mode vanished on
    // its aggregate).
    std::vector<double> a;
    std::vector<std::uint8_t> fixed;  // per unknown

    static constexpr int kStencil = 25;
    static constexpr int slot(int di, int dj) { return 5 * (dj + 2) + di + 2; }
    void resize(int nuIn, int nvIn, int bIn);
    std::int64_t count() const { return std::int64_t(nu) * nv; }
    std::size_t dofs() const { return std::size_t(count()) * std::size_t(b); }
    std::size_t blockSize() const { return std::size_t(b) * std::size_t(b); }
    double* block(std::int64_t k, int s) {
        return &a[(std::size_t(k) * kStencil + std::size_t(s)) * blockSize()];
    }
    const double* block(std::int64_t k, int s) const {
        return &a[(std::size_t(k) * kStencil + std::size_t(s)) * blockSize()];
    }
    bool contains(int i, int j) const { return i >= 0 && j >= 0 && i < nu && j < nv; }
    // Fixed unknowns: zero their rows and columns, 1 on the diagonal.
    void imposeFixed();
    // y = A x (b unknowns a vertex, vertex-major).
    void apply(const double* x, double* y) const;
    // y = r − A x.
    void residual(const double* r, const double* x, double* y) const;
};

// Alternating line Gauss–Seidel: every row of the grid solved exactly against the current values
// of the rest (a banded Cholesky factor each, half band 3b − 1), then every column; lines in 5
// colours (line mod 5) so that the lines of a colour do not touch. `backward` runs the adjoint
// (columns then rows, colours in reverse), so that a forward sweep followed by a backward one is
// symmetric.
class LineSmoother {
public:
    void factor(const BlockGrid& g);
    void sweep(const BlockGrid& g, const double* r, double* z, bool backward) const;

private:
    void relax(const BlockGrid& g, int direction, int line, const double* r, double* z) const;
    int band_ = 0;
    std::vector<double> factors_[2];  // rows (direction 0), columns (1): each line's L, by rows
    mutable std::vector<double> y_;   // a line's right-hand side, then its solution
};

// a = L Lᵀ in place: a row-major n × n, L in its lower triangle; a pivot is held at `floor`
// times its diagonal or more (only rounding takes a positive definite matrix's pivot below).
void denseCholesky(double* a, std::size_t n, double floor);

// The coarsest grid's dense Cholesky factor.
class DenseSolve {
public:
    void factor(const BlockGrid& g);
    void solve(const double* r, double* z) const;

private:
    std::size_t n_ = 0;
    std::vector<double> l_;
};

}  // namespace cloth
