// The block-stencil grid of cpu/block_grid.h: its product, its line smoother and the dense
// coarsest solve.
#include "cpu/block_grid.h"

#include <algorithm>
#include <cmath>

#include "cpu/block_kernels.h"

namespace cloth {

void BlockGrid::resize(int nuIn, int nvIn, int bIn) {
    nu = nuIn;
    nv = nvIn;
    b = bIn;
    a.assign(std::size_t(count()) * kStencil * blockSize(), 0.0);
    fixed.assign(dofs(), 0);
}

void BlockGrid::imposeFixed() {
    const std::size_t B = std::size_t(b);
    for (std::int64_t k = 0; k < count(); ++k) {
        const int i = int(k % nu), j = int(k / nu);
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
                if (!contains(i + di, j + dj)) continue;
                const std::int64_t q = k + std::int64_t(dj) * nu + di;
                double* blk = block(k, slot(di, dj));
                for (std::size_t r = 0; r < B; ++r)
                    for (std::size_t c = 0; c < B; ++c)
                        if (fixed[std::size_t(k) * B + r] || fixed[std::size_t(q) * B + c])
                            blk[c * B + r] = (q == k && r == c) ? 1.0 : 0.0;
            }
    }
}

namespace {

// y = r − A x on vertices [begin, end) (r null: y = −A x).
template <int kB>
void residualRows(const BlockGrid& g, const double* r, const double* x, double* y) {
    const int b = blocks::size<kB>(g.b);
    const std::size_t B = std::size_t(b);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const int i = int(k % g.nu), j = int(k / g.nu);
        double* out = y + std::size_t(k) * B;
        for (std::size_t row = 0; row < B; ++row) out[row] = r ? r[std::size_t(k) * B + row] : 0;
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di)
                if (g.contains(i + di, j + dj))
                    blocks::subtractProduct<kB>(
                        g.block(k, BlockGrid::slot(di, dj)),
                        x + std::size_t(k + std::int64_t(dj) * g.nu + di) * B, out, b);
    }
}

}  // namespace

void BlockGrid::residual(const double* r, const double* x, double* y) const {
    blocks::dispatch(b, [&](auto kB) { residualRows<decltype(kB)::value>(*this, r, x, y); });
}

void BlockGrid::apply(const double* x, double* y) const {
    residual(nullptr, x, y);
    for (std::size_t e = 0; e < dofs(); ++e) y[e] = -y[e];
}

// Line `line` of `direction` (0: the row j = line, 1: the column i = line), vertex a along it.
static std::int64_t lineVertex(const BlockGrid& g, int direction, int line, int a) {
    return direction == 0 ? std::int64_t(line) * g.nu + a : std::int64_t(a) * g.nu + line;
}

void LineSmoother::factor(const BlockGrid& g) {
    const int b = g.b;
    band_ = 3 * b - 1;  // a block two vertices along: columns up to 2b + b − 1 from the diagonal
    const std::size_t width = std::size_t(band_) + 1;
    for (int direction = 0; direction < 2; ++direction) {
        const int lines = direction == 0 ? g.nv : g.nu, length = direction == 0 ? g.nu : g.nv;
        const std::size_t dofs = std::size_t(length) * std::size_t(b);
        std::vector<double>& f = factors_[direction];
        f.assign(std::size_t(lines) * dofs * width, 0.0);
        for (int line = 0; line < lines; ++line) {
            double* l = &f[std::size_t(line) * dofs * width];
            auto entry = [&](std::size_t row, std::size_t col) -> double& {
                return l[row * width + (std::size_t(band_) - (row - col))];
            };
            for (int a = 0; a < length; ++a)
                for (int c = std::max(0, a - 2); c <= a; ++c) {
                    const int d = c - a;
                    const double* blk =
                        g.block(lineVertex(g, direction, line, a),
                                direction == 0 ? BlockGrid::slot(d, 0) : BlockGrid::slot(0, d));
                    for (int row = 0; row < b; ++row)
                        for (int col = 0; col < b; ++col) {
                            const std::size_t R = std::size_t(a * b + row);
                            const std::size_t C = std::size_t(c * b + col);
                            if (C <= R) entry(R, C) = blk[col * b + row];
                        }
                }
            for (std::size_t i = 0; i < dofs; ++i) {  // banded Cholesky in place
                const std::size_t lo = i >= std::size_t(band_) ? i - std::size_t(band_) : 0;
                const double diagonal = entry(i, i);
                for (std::size_t j = lo; j <= i; ++j) {
                    double s = entry(i, j);
                    const std::size_t qlo =
                        std::max(lo, j >= std::size_t(band_) ? j - std::size_t(band_) : 0);
                    for (std::size_t q = qlo; q < j; ++q) s -= entry(i, q) * entry(j, q);
                    entry(i, j) = i == j ? std::sqrt(std::max(s, 1e-12 * diagonal + 1e-300))
                                         : s / entry(j, j);
                }
            }
        }
    }
}

namespace {

// y = r − (the stencil off the line) z on line `line` of `direction`.
template <int kB>
void offLineResidual(const BlockGrid& g, int direction, int line, const double* r, const double* z,
                     double* y) {
    const int b = blocks::size<kB>(g.b), length = direction == 0 ? g.nu : g.nv;
    const std::size_t B = std::size_t(b);
    for (int a = 0; a < length; ++a) {
        const std::int64_t k = lineVertex(g, direction, line, a);
        const int i = int(k % g.nu), j = int(k / g.nu);
        double* out = &y[std::size_t(a) * B];
        for (std::size_t row = 0; row < B; ++row) out[row] = r[std::size_t(k) * B + row];
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di)
                if ((direction == 0 ? dj : di) != 0 && g.contains(i + di, j + dj))
                    blocks::subtractProduct<kB>(
                        g.block(k, BlockGrid::slot(di, dj)),
                        z + std::size_t(k + std::int64_t(dj) * g.nu + di) * B, out, b);
    }
}

}  // namespace

void LineSmoother::relax(const BlockGrid& g, int direction, int line, const double* r,
                         double* z) const {
    const int length = direction == 0 ? g.nu : g.nv;
    const std::size_t B = std::size_t(g.b), dofs = std::size_t(length) * B;
    const std::size_t band = std::size_t(band_), width = band + 1;
    std::vector<double>& y = y_;
    y.resize(dofs);
    blocks::dispatch(g.b, [&](auto kB) {
        offLineResidual<decltype(kB)::value>(g, direction, line, r, z, y.data());
    });
    // L L^T z = y. Row i of L holds columns i − band … i contiguously (the diagonal last).
    const double* l = &factors_[direction][std::size_t(line) * dofs * width];
    for (std::size_t i = 0; i < dofs; ++i) {  // L y' = y
        const std::size_t lo = i >= band ? i - band : 0;
        const double* row = l + i * width + band - (i - lo);
        const double* yl = y.data() + lo;
        double s = y[i];
        for (std::size_t q = 0; q < i - lo; ++q) s -= row[q] * yl[q];
        y[i] = s / row[i - lo];
    }
    for (std::size_t i = dofs; i-- > 0;) {  // Lᵀ z = y', column by column: row i of L
        const std::size_t lo = i >= band ? i - band : 0;
        const double* row = l + i * width + band - (i - lo);
        const double zi = y[i] / row[i - lo];
        y[i] = zi;
        double* yl = y.data() + lo;
        for (std::size_t q = 0; q < i - lo; ++q) yl[q] -= row[q] * zi;
    }
    for (int a = 0; a < length; ++a) {
        const std::int64_t k = lineVertex(g, direction, line, a);
        for (std::size_t row = 0; row < B; ++row)
            z[std::size_t(k) * B + row] = y[std::size_t(a) * B + row];
    }
}

void LineSmoother::sweep(const BlockGrid& g, const double* r, double* z, bool backward) const {
    for (int step = 0; step < 2; ++step) {
        const int direction = backward ? 1 - step : step;
        const int lines = direction == 0 ? g.nv : g.nu;
        for (int c = 0; c < 5; ++c) {
            const int colour = backward ? 4 - c : c;
            if (!backward)
                for (int line = colour; line < lines; line += 5) relax(g, direction, line, r, z);
            else
                for (int line = lines - 1; line >= 0; --line)
                    if (line % 5 == colour) relax(g, direction, line, r, z);
        }
    }
}

void DenseSolve::factor(const BlockGrid& g) {
    n_ = g.dofs();
    l_.assign(n_ * n_, 0.0);
    const std::size_t B = std::size_t(g.b);
    for (std::int64_t k = 0; k < g.count(); ++k) {
        const int i = int(k % g.nu), j = int(k / g.nu);
        for (int dj = -2; dj <= 2; ++dj)
            for (int di = -2; di <= 2; ++di) {
                if (!g.contains(i + di, j + dj)) continue;
                const std::size_t q = std::size_t(k + std::int64_t(dj) * g.nu + di);
                const double* blk = g.block(k, BlockGrid::slot(di, dj));
                for (std::size_t r = 0; r < B; ++r)
                    for (std::size_t c = 0; c < B; ++c)
                        l_[(std::size_t(k) * B + r) * n_ + q * B + c] = blk[c * B + r];
            }
    }
    denseCholesky(l_.data(), n_, 1e-12);
}

void denseCholesky(double* a, std::size_t n, double floor) {
    for (std::size_t j = 0; j < n; ++j) {  // Cholesky–Banachiewicz, column by column
        const double diagonal = a[j * n + j];
        for (std::size_t i = j; i < n; ++i) {
            double s = a[i * n + j];
            for (std::size_t m = 0; m < j; ++m) s -= a[i * n + m] * a[j * n + m];
            a[i * n + j] =
                i == j ? std::sqrt(std::max(s, floor * diagonal + 1e-300)) : s / a[j * n + j];
        }
    }
}

void DenseSolve::solve(const double* r, double* z) const {
    for (std::size_t i = 0; i < n_; ++i) {
        double s = r[i];
        for (std::size_t m = 0; m < i; ++m) s -= l_[i * n_ + m] * z[m];
        z[i] = s / l_[i * n_ + i];
    }
    for (std::size_t i = n_; i-- > 0;) {
        double s = z[i];
        for (std::size_t m = i + 1; m < n_; ++m) s -= l_[m * n_ + i] * z[m];
        z[i] = s / l_[i * n_ + i];
    }
}

}  // namespace cloth
