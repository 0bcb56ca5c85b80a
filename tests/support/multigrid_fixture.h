// The multigrid tests' system (tests/cpu/multigrid_test.cpp, aggregation_test.cpp): implicit
// Euler's matrix of the drape cloth at a sagged, crumpled state, linearised by the geometric
// multigrid's fine grid.
#pragma once

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cpu/cpu_multigrid.h"
#include "scene/scene_loader.h"
#include "support/draws.h"

namespace cloth::test {

// implicit_euler's system of the drape cloth at `cells`² vertices, stretch `stretch` [N/m] (0: the
// cotton preset's), at Δt = 1/60, linearised at a sagged, slightly crumpled state (every spring
// strained a little, some compressed), pinned at two corners.
struct Fixture {
    Scene scene;
    Grid grid;
    std::vector<StencilSpring<double>> springs;
    Soa3<double> x;
    std::vector<double> inverseMass;
    std::vector<std::uint8_t> pinned;
    CpuMultigrid<double>::FineSystem system;
    CpuMultigrid<double> multigrid;

    Fixture(int cells, double stretch, std::vector<std::string> extra = {}) {
        std::ostringstream resolution, material;
        resolution << "cloth.resolution=[" << cells << "," << cells << "]";
        material << "material.stretch=" << stretch;
        std::vector<std::string> sets = {resolution.str(), "integrator.dt=0.016667"};
        if (stretch > 0) sets.push_back(material.str());
        sets.insert(sets.end(), extra.begin(), extra.end());
        scene = loadScene(CLOTH_SOURCE_DIR "/scenes/drape.json", sets);
        grid = scene.grid();
        springs = activeSprings<double>(scene);
        const std::int64_t n = grid.count();
        x.assign(n, Vec3<double>(0));
        std::mt19937 random(7);
        std::uniform_real_distribution<double> jitter(-0.05, 0.05);
        for (int j = 0; j < grid.nv; ++j)
            for (int i = 0; i < grid.nu; ++i) {
                const double s = double(i) / (grid.nu - 1), t = double(j) / (grid.nv - 1);
                glm::dvec3 p = grid.restPosition(i, j) * 1.002;  // strained 0.2 %
                p.y -= 0.1 * std::sin(3.14159 * s) * std::sin(3.14159 * t);
                p += drawVec3(jitter, random) * grid.du;
                x.set(grid.index(i, j), p);
                inverseMass.push_back(1 / scene.vertexMass(i, j));
            }
        pinned.assign(std::size_t(n), 0);
        pinned[0] = pinned[std::size_t(grid.nu - 1)] = 1;
        system.nu = grid.nu;
        system.nv = grid.nv;
        system.springs = &springs;
        system.bending = bendingWeights(grid, scene.bendingStiffness());
        system.x = &x;
        system.inverseMass = inverseMass.data();
        system.pinned = pinned.data();
        system.h = scene.integrator.dt;
        system.drag = 1 + system.h * scene.dampingRate();
        system.springDamping = scene.springDamping() > 0;
        multigrid.configure(grid.nu, grid.nv);
        multigrid.linearise(system, CycleThreads{});
    }
    std::vector<Vec3<double>> random(unsigned seed) const {
        std::mt19937 g(seed);
        std::normal_distribution<double> normal;
        std::vector<Vec3<double>> v(std::size_t(grid.count()));
        for (std::size_t k = 0; k < v.size(); ++k)
            if (!pinned[k]) v[k] = {normal(g), normal(g), normal(g)};
        return v;
    }
    std::vector<Vec3<double>> cycle(const std::vector<Vec3<double>>& r) {
        std::vector<Vec3<double>> z(r.size());
        multigrid.apply(r, z, CycleThreads{});
        return z;
    }
    std::vector<Vec3<double>> product(const std::vector<Vec3<double>>& p) const {
        std::vector<Vec3<double>> out(p.size());
        system.apply(p.data(), out.data(), 0, grid.count());
        return out;
    }
    // The energy-norm contraction of the stationary iteration x ← x + V (b − A x), per cycle
    // over its last of `cycles` cycles.
    double contraction(int cycles) {
        const auto exact = random(3);
        const auto b = product(exact);
        std::vector<Vec3<double>> solution(b.size());
        auto energy = [&] {
            std::vector<Vec3<double>> e(b.size());
            for (std::size_t k = 0; k < e.size(); ++k) e[k] = exact[k] - solution[k];
            const auto ae = product(e);
            double s = 0;
            for (std::size_t k = 0; k < e.size(); ++k) s += glm::dot(e[k], ae[k]);
            return std::sqrt(s);
        };
        double last = energy(), factor = 0;
        for (int it = 0; it < cycles; ++it) {
            const auto ax = product(solution);
            std::vector<Vec3<double>> r(b.size());
            for (std::size_t k = 0; k < r.size(); ++k) r[k] = b[k] - ax[k];
            const auto z = cycle(r);
            for (std::size_t k = 0; k < solution.size(); ++k) solution[k] += z[k];
            const double now = energy();
            factor = now / last;
            last = now;
        }
        return factor;
    }
};

inline double dot(const std::vector<Vec3<double>>& a, const std::vector<Vec3<double>>& b) {
    double s = 0;
    for (std::size_t k = 0; k < a.size(); ++k) s += glm::dot(a[k], b[k]);
    return s;
}

}  // namespace cloth::test
