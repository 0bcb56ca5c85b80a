// SoA against padded vec4 rows for the CPU force pass (docs/performance.md, "CPU: SIMD layout,
// vectorised gather, fused passes"). The same kernel, the solver's (core/spring_math.h
// coefficients of the 6 upward springs into a ring of 3 rows, then the 12-neighbour gather of
// each interior vertex), over the same positions stored two ways: three arrays x[], y[], z[]
// (stride 1) or one array of vec4 {x, y, z, w} (stride 4). GCC vectorises both across the row;
// the vec4 loads are strided and need permutes. Not part of the build:
//   g++ -std=c++20 -O3 -ffp-contract=off -fno-math-errno -mavx512f -mavx512vl -mavx512bw \
//       -mavx512dq -mprefer-vector-width=512 -Isrc bench/cpu_layout.cpp -o /tmp/cpu_layout
//   flock /tmp/clothsim-timing.lock /tmp/cpu_layout
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "model/spring_math.h"

namespace {

constexpr int kDi[12] = {1, -1, 0, 0, 1, -1, 1, -1, 2, -2, 0, 0};
constexpr int kDj[12] = {0, 0, 1, -1, 1, 1, -1, -1, 0, 0, 2, -2};
constexpr int kUp[6] = {0, 2, 4, 5, 8, 10};                      // upward springs
constexpr int kSlot[12] = {0, 0, 1, 1, 2, 3, 3, 2, 4, 4, 5, 5};  // … and whose reverse
constexpr bool kUpward[12] = {1, 0, 1, 0, 1, 1, 0, 0, 1, 0, 1, 0};

// Positions of vertex k: p[S*k], p[S*k + plane] for plane y, z; S = 1 with plane = N² (SoA),
// S = 4 with plane = 1 (vec4).
template <typename T, int S>
double forcePass(const T* __restrict p, T* __restrict f, T* __restrict ring, int n,
                 std::ptrdiff_t plane) {
    const T k = 100, l = T(0.01);
    auto at = [&](std::ptrdiff_t q, int c) { return p[S * q + c * plane]; };
    auto coefficientRow = [&](int j) {
        T* r = ring + std::size_t(j % 3) * 6 * n;
        for (int u = 0; u < 6; ++u) {
            const int s = kUp[u];
            const std::ptrdiff_t d = std::ptrdiff_t(kDj[s]) * n + kDi[s];
            for (int i = 2; i < n - 2; ++i) {
                const std::ptrdiff_t q = std::ptrdiff_t(j) * n + i;
                r[u * n + i] =
                    cloth::springCoefficient(at(q + d, 0) - at(q, 0), at(q + d, 1) - at(q, 1),
                                             at(q + d, 2) - at(q, 2), k, l);
            }
        }
    };
    coefficientRow(0);
    coefficientRow(1);
    for (int j = 2; j < n - 2; ++j) {
        coefficientRow(j);
        const T* cs[12];  // spring s's coefficient for column i is cs[s][i]
        for (int s = 0; s < 12; ++s)
            cs[s] = ring + std::size_t((kUpward[s] ? j : j + kDj[s]) % 3) * 6 * n + kSlot[s] * n +
                    (kUpward[s] ? 0 : kDi[s]);
#pragma GCC ivdep
        for (int i = 2; i < n - 2; ++i) {
            const std::ptrdiff_t q = std::ptrdiff_t(j) * n + i;
            T x = 0, y = 0, z = 0;
#pragma GCC unroll 12
            for (int s = 0; s < 12; ++s) {
                const T c = cs[s][i];
                const std::ptrdiff_t d = std::ptrdiff_t(kDj[s]) * n + kDi[s];
                x += c * (at(q + d, 0) - at(q, 0));
                y += c * (at(q + d, 1) - at(q, 1));
                z += c * (at(q + d, 2) - at(q, 2));
            }
            f[S * q] = x;
            f[S * q + plane] = y;
            f[S * q + 2 * plane] = z;
        }
    }
    return double(f[S * (std::ptrdiff_t(n) * n / 2 + n / 2)]);
}

template <typename T, int S>
double timePass(int n) {
    const std::size_t cells = std::size_t(n) * n;
    const std::ptrdiff_t plane = S == 1 ? std::ptrdiff_t(cells) : 1;
    std::vector<T> p(cells * (S == 1 ? 3 : 4)), f(p.size()), ring(std::size_t(3) * 6 * n);
    for (std::size_t q = 0; q < cells; ++q)
        for (int c = 0; c < 3; ++c)
            p[S * q + c * plane] = T(0.01) * T(c == 0 ? q % n : c == 1 ? q / n : (q * 7) % 5);
    double best = 1e30, sink = 0;
    const int reps = n > 1000 ? 5 : 200;
    for (int trial = 0; trial < 5; ++trial) {
        const auto t0 = std::chrono::steady_clock::now();
        for (int r = 0; r < reps; ++r)
            sink += forcePass<T, S>(p.data(), f.data(), ring.data(), n, plane);
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        best = std::min(best, s / reps / double(cells));
    }
    if (sink == 12345) std::puts("");
    return best * 1e9;  // ns per vertex
}

}  // namespace

int main() {
    std::printf("force pass, 1 thread, ns per vertex (best of 5)\n%6s %12s %12s %12s %12s\n",
                "side", "SoA float", "vec4 float", "SoA double", "vec4 double");
    for (int n : {256, 2048})
        std::printf("%6d %12.2f %12.2f %12.2f %12.2f\n", n, timePass<float, 1>(n),
                    timePass<float, 4>(n), timePass<double, 1>(n), timePass<double, 4>(n));
}
