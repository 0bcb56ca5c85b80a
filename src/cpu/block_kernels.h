// Small dense kernels on the blocks of a block grid (cpu/block_grid.h), with the block sizes
// known at compile time for the sizes the aggregation multigrid uses (3 unknowns a vertex on the
// fine grid, 6 + k on the coarse ones): the compiler then unrolls and vectorises the loops that
// a run-time size leaves scalar. kB = 0 takes the size at run time.
#pragma once

#include <type_traits>

namespace cloth::blocks {

template <int kB>
constexpr int size(int b) {
    return kB ? kB : b;
}

// Calls fn(std::integral_constant<int, B>) with B = b for the sizes compiled, 0 otherwise.
template <typename Fn>
void dispatch(int b, Fn&& fn) {
    switch (b) {
        case 3:
            fn(std::integral_constant<int, 3>{});
            break;
        case 10:
            fn(std::integral_constant<int, 10>{});
            break;
        case 12:
            fn(std::integral_constant<int, 12>{});
            break;
        case 14:
            fn(std::integral_constant<int, 14>{});
            break;
        case 16:
            fn(std::integral_constant<int, 16>{});
            break;
        case 18:
            fn(std::integral_constant<int, 18>{});
            break;
        default:
            fn(std::integral_constant<int, 0>{});
            break;
    }
}

// A grid's blocks are column-major (entry (r, c) at c n + r), so that a block times a vector is
// a sum of its columns: loops over contiguous entries without a reduction, which the compiler
// vectorises without reordering a sum.

// out −= a × x, a of n × n (column-major).
template <int kN>
inline void subtractProduct(const double* __restrict a, const double* __restrict x,
                            double* __restrict out, int n) {
    n = size<kN>(n);
    for (int c = 0; c < n; ++c) {
        const double xc = x[c];
        for (int r = 0; r < n; ++r) out[r] -= a[c * n + r] * xc;
    }
}

// out (n × m) += s · a (n × n, column-major) × p (n × m, row-major), out row-major.
template <int kN, int kM>
inline void multiplyAdd(const double* __restrict a, const double* __restrict p,
                        double* __restrict out, int n, int m, double s = 1.0) {
    n = size<kN>(n);
    m = size<kM>(m);
    for (int r = 0; r < n; ++r)
        for (int q = 0; q < n; ++q) {
            const double f = s * a[q * n + r];
            for (int c = 0; c < m; ++c) out[r * m + c] += f * p[q * m + c];
        }
}

// out (m × m, column-major) += pᵀ a, p and a of n × m (row-major).
template <int kN, int kM>
inline void addTransposedProduct(const double* __restrict p, const double* __restrict a,
                                 double* __restrict out, int n, int m) {
    n = size<kN>(n);
    m = size<kM>(m);
    for (int r = 0; r < n; ++r)
        for (int y = 0; y < m; ++y) {
            const double f = a[r * m + y];
            for (int x = 0; x < m; ++x) out[y * m + x] += p[r * m + x] * f;
        }
}

}  // namespace cloth::blocks
