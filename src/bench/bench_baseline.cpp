#include "bench/bench_baseline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <thread>

namespace cloth::app {
namespace {

// The 12 neighbour offsets in the order the seed's loop visits them.
constexpr int kDi[12] = {1, -1, 0, 0, 1, 1, -1, -1, 2, -2, 0, 0};
constexpr int kDj[12] = {0, 0, 1, -1, 1, -1, 1, -1, 0, 0, 2, -2};

}  // namespace

BaselineCloth::BaselineCloth(const Scene& scene)
    : grid_(scene.grid()),
      nu_(grid_.nu),
      nv_(grid_.nv),
      dt_(scene.integrator.dt),
      mass_(scene.material ? scene.vertexMass(1, 1) : scene.cloth.mass),
      damping_(scene.material ? scene.dampingRate() * scene.vertexMass(1, 1) : scene.damping),
      k_{scene.material ? scene.slotStiffness(0) : scene.springs.structural,
         scene.material ? scene.slotStiffness(4) : scene.springs.shear,
         scene.material ? 0.0 : scene.springs.bend},
      gravity_{scene.gravity.x, scene.gravity.y, scene.gravity.z} {
    const std::size_t n = std::size_t(nu_) * nv_;
    x_.resize(n);
    v_.assign(n, V3{0, 0, 0});
    xNext_.resize(n);
    vNext_.resize(n);
    pinned_.assign(n, 0);
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i) {
            const glm::dvec3 p = grid_.restPosition(i, j);
            x_[std::size_t(j) * nu_ + i] = V3{p.x, p.y, p.z};
        }
    for (const Pin& p : scene.pins) pinned_[std::size_t(p.j) * nu_ + p.i] = 1;
    // û and v̂ need not be orthogonal (a skewed cloth): L is the length of the rest offset
    // di·du·û + dj·dv·v̂, not √((di·du)² + (dj·dv)²); uniform per offset on the regular grid.
    for (int s = 0; s < 12; ++s) rest_[s] = grid_.restLength(kDi[s], kDj[s]);
}

void BaselineCloth::step(long n) {
    for (long s = 0; s < n; ++s) stepOnce();
}

// The seed's loop as it was written: for every vertex, for every neighbour offset, a bounds
// check, the spring force F = K(|d| − L) d/|d| (seed eq. (2)) with L = |di·du·û + dj·dv·v̂|
// (DESIGN.md §2), then v += Δt((F − μv)/m + g), x += Δt·v_old (seed eq. (6)) into the next arrays.
void BaselineCloth::stepOnce() {
    const int* di = kDi;
    const int* dj = kDj;
    static const int family[12] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2};
    for (int j = 0; j < nv_; ++j) {
        for (int i = 0; i < nu_; ++i) {
            const int k = j * nu_ + i;
            double fx = 0, fy = 0, fz = 0;
            for (int s = 0; s < 12; ++s) {
                const int ii = i + di[s], jj = j + dj[s];
                if (ii < 0 || ii >= nu_ || jj < 0 || jj >= nv_) continue;
                const double stiffness = k_[family[s]];
                if (stiffness == 0) continue;
                const double rest = rest_[s];
                const int q = jj * nu_ + ii;
                const double dx = x_[q].x - x_[k].x, dy = x_[q].y - x_[k].y, dz = x_[q].z - x_[k].z;
                const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
                if (len < 1e-12 * rest) continue;
                const double f = stiffness * (len - rest) / len;
                fx += f * dx;
                fy += f * dy;
                fz += f * dz;
            }
            const V3 v = v_[k];
            if (pinned_[k]) {
                xNext_[k] = x_[k];
                vNext_[k] = V3{0, 0, 0};
                continue;
            }
            vNext_[k] = V3{v.x + dt_ * ((fx - damping_ * v.x) / mass_ + gravity_.x),
                           v.y + dt_ * ((fy - damping_ * v.y) / mass_ + gravity_.y),
                           v.z + dt_ * ((fz - damping_ * v.z) / mass_ + gravity_.z)};
            xNext_[k] = V3{x_[k].x + dt_ * v.x, x_[k].y + dt_ * v.y, x_[k].z + dt_ * v.z};
        }
    }
    x_.swap(xNext_);
    v_.swap(vNext_);
}

double measureTriadBandwidth(std::size_t bytesEach, int repeats) {
    const std::size_t n = bytesEach / sizeof(double);
    std::vector<double> a(n), b(n, 1.0), c(n, 2.0);
    const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const double s = 3.0;
    auto triad = [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) a[i] = b[i] + s * c[i];
    };
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= repeats; ++r) {  // r = 0 is the warm-up (first touch of a)
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::thread> team;
        for (int t = 1; t < threads; ++t)
            team.emplace_back(triad, n * t / threads, n * (t + 1) / threads);
        triad(0, n / threads);
        for (auto& th : team) th.join();
        const double sec =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (r > 0) best = std::min(best, sec);
    }
    if (a[n / 2] != 7.0) return 0;  // keeps the loop from being optimised away
    return 3.0 * double(n * sizeof(double)) / best;
}

}  // namespace cloth::app
