// CpuSolver as the step control's StepCheck (solver/step_check.h): the step's start is a copy of
// the state arrays, and the step is measured in double from them, spring for spring as
// largestStretchGrowth (solver/diagnostics.cpp) measures the states read back, so the control
// decides as it would on read() and write(), without converting the state every step.
#include <algorithm>
#include <cmath>
#include <limits>

#include "cpu/cpu_solver.h"

namespace cloth {

template <typename T>
void CpuSolver<T>::keep() {
    keptX_ = x_;
    keptV_ = v_;
    keptTime_ = time();
}

template <typename T>
double CpuSolver<T>::stretchGrowth() {
    if (!features_.structural) return 0;  // as largestStretchGrowth: no structural spring
    auto length = [](const Soa3<T>& x, std::int64_t a, std::int64_t b) {
        const double dx = double(x.x[b]) - x.x[a], dy = double(x.y[b]) - x.y[a],
                     dz = double(x.z[b]) - x.z[a];
        return std::sqrt(dx * dx + dy * dy + dz * dz);
    };
    double largest = 0;
    for (auto [di, dj] : {std::pair{1, 0}, {0, 1}}) {
        const double rest = grid_.restLength(di, dj);
        for (int j = 0; j + dj < grid_.nv; ++j)
            for (int i = 0; i + di < grid_.nu; ++i) {
                const std::int64_t a = grid_.index(i, j), b = grid_.index(i + di, j + dj);
                const double was = length(keptX_, a, b), is = length(x_, a, b);
                if (!std::isfinite(was) || !std::isfinite(is))
                    return std::numeric_limits<double>::infinity();
                largest = std::max(largest, (std::max(is, rest) - std::max(was, rest)) / rest);
            }
    }
    return largest;
}

template <typename T>
void CpuSolver<T>::restore() {
    x_ = keptX_;
    v_ = keptV_;
    // The pins need nothing: a pinned vertex is where its pin holds it, or follows a collider
    // posed by the time.
    startAfresh(keptTime_);
}

// cpu_solver.h declares the class instantiations extern: these members are instantiated here.
#define CLOTH_INSTANTIATE(T)                       \
    template void CpuSolver<T>::keep();            \
    template double CpuSolver<T>::stretchGrowth(); \
    template void CpuSolver<T>::restore();
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
