// Nonlinear backward Euler, the oracle of vbd (docs/integrators.md "vbd"): the step that Vertex
// Block Descent's iterations converge to, solved here the plain way — Newton's method on the
// whole system, its Jacobian by central differences, dense Gaussian elimination. Written from
// the page alone; slow, and meant for grids of a few dozen vertices.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "reference/reference.h"
#include "reference/vector_ops.h"

namespace ref {
namespace {

// Solves a x = b (n × n, row-major) by Gaussian elimination with partial pivoting.
std::vector<double> solveDense(std::vector<double> a, std::vector<double> b) {
    const std::size_t n = b.size();
    for (std::size_t c = 0; c < n; ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < n; ++r)
            if (std::fabs(a[r * n + c]) > std::fabs(a[pivot * n + c])) pivot = r;
        if (a[pivot * n + c] == 0) throw std::runtime_error("backward Euler: singular Jacobian");
        for (std::size_t k = 0; k < n; ++k) std::swap(a[c * n + k], a[pivot * n + k]);
        std::swap(b[c], b[pivot]);
        for (std::size_t r = c + 1; r < n; ++r) {
            const double f = a[r * n + c] / a[c * n + c];
            for (std::size_t k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
            b[r] -= f * b[c];
        }
    }
    std::vector<double> x(n);
    for (std::size_t r = n; r-- > 0;) {
        double s = b[r];
        for (std::size_t k = r + 1; k < n; ++k) s -= a[r * n + k] * x[k];
        x[r] = s / a[r * n + r];
    }
    return x;
}

}  // namespace

// Backward Euler with x_{n+1} = x, v_{n+1} = (x − x_n)/h: on every free vertex
//   m_k (x − x_n − h v_n)/h² = F_s(x) + F_b(x) + F_w(x_n) + F_β(x_n, (x − x_n)/h) + m_k g
//                              − μ_k (x − x_n)/h,
// springs and bending at the new positions, the wind at the old ones (explicit), the spring
// damping along the springs' directions at x_n (implicit Euler's D), the drag implicit. Pinned
// vertices sit at their pin from the start. Newton from x_n + h v_n until the largest
// correction is below 1e-14 m.
void Simulation::stepBackwardEuler() {
    const double h = prm_.dt;
    const std::size_t n = p_.size();
    const std::vector<V3> xn = p_, vn = v_;
    std::vector<V3> wind(n, V3{0, 0, 0});
    for (int j = 0; j < prm_.nv; ++j)
        for (int i = 0; i < prm_.nu; ++i)
            if (prm_.wind) wind[j * prm_.nu + i] = windForce(xn, i, j);
    std::vector<V3> x(n), unusedV(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = add(xn[k], scale(h, vn[k]));
    pin(x, unusedV);
    std::vector<int> free;
    for (std::size_t k = 0; k < n; ++k)
        if (!pinned_[k]) free.push_back(int(k));
    const std::size_t dofs = 3 * free.size();

    auto residual = [&](const std::vector<V3>& y) {
        std::vector<V3> f(n, V3{0, 0, 0});
        for (int j = 0; j < prm_.nv; ++j)
            for (int i = 0; i < prm_.nu; ++i) f[j * prm_.nu + i] = springForces(y, i, j);
        addBending(y, f);
        std::vector<V3> displacementRate(n);
        for (std::size_t k = 0; k < n; ++k) displacementRate[k] = scale(1 / h, sub(y[k], xn[k]));
        addSpringDamping(xn, displacementRate, f);
        std::vector<double> r(dofs);
        for (std::size_t a = 0; a < free.size(); ++a) {
            const int k = free[a];
            const V3 inertia = scale(mass_[k] / (h * h), sub(sub(y[k], xn[k]), scale(h, vn[k])));
            const V3 rest = add(add(f[k], wind[k]), scale(mass_[k], prm_.gravity));
            const V3 rk = add(sub(inertia, rest), scale(drag(k), displacementRate[k]));
            for (int c = 0; c < 3; ++c) r[3 * a + c] = rk[c];
        }
        return r;
    };

    for (int iteration = 0; iteration < 100; ++iteration) {
        const std::vector<double> r = residual(x);
        std::vector<double> jacobian(dofs * dofs);
        const double eps = 1e-7;
        for (std::size_t col = 0; col < dofs; ++col) {
            std::vector<V3> plus = x, minus = x;
            plus[free[col / 3]][col % 3] += eps;
            minus[free[col / 3]][col % 3] -= eps;
            const std::vector<double> rp = residual(plus), rm = residual(minus);
            for (std::size_t row = 0; row < dofs; ++row)
                jacobian[row * dofs + col] = (rp[row] - rm[row]) / (2 * eps);
        }
        std::vector<double> minusR(dofs);
        for (std::size_t row = 0; row < dofs; ++row) minusR[row] = -r[row];
        const std::vector<double> dx = solveDense(std::move(jacobian), minusR);
        double largest = 0;
        for (std::size_t row = 0; row < dofs; ++row) {
            x[free[row / 3]][row % 3] += dx[row];
            largest = std::max(largest, std::fabs(dx[row]));
        }
        if (largest < 1e-14) break;
    }
    for (std::size_t k = 0; k < n; ++k) {
        v_[k] = scale(1 / h, sub(x[k], xn[k]));
        p_[k] = x[k];
    }
    pinAndCollide(p_, v_);
}

}  // namespace ref
