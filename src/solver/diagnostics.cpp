#include "solver/diagnostics.h"

#include <cmath>

namespace cloth {

Energy energy(const Scene& scene, const SimState& state) {
    const Grid g = scene.grid();
    const double m = scene.cloth.mass;
    Energy e;
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            const auto k = g.index(i, j);
            const glm::dvec3& p = state.positions[k];
            e.kinetic += 0.5 * m * glm::dot(state.velocities[k], state.velocities[k]);
            e.gravity -= m * glm::dot(scene.gravity, p);
            for (const SpringOffset& o : kSpringOffsets) {
                // Each spring once: only the offsets pointing "forward" in index order.
                if (o.dj < 0 || (o.dj == 0 && o.di < 0)) continue;
                const double stiffness = scene.springs.of(o.family);
                if (stiffness <= 0 || !g.contains(i + o.di, j + o.dj)) continue;
                const double stretch =
                    glm::length(state.positions[g.index(i + o.di, j + o.dj)] - p) -
                    g.restLength(o.di, o.dj);
                e.spring += 0.5 * stiffness * stretch * stretch;
            }
        }
    }
    return e;
}

double maxStrain(const Scene& scene, const SimState& state) {
    const Grid g = scene.grid();
    double strain = 0;
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            for (auto [di, dj] : {std::pair{1, 0}, {0, 1}}) {
                if (!g.contains(i + di, j + dj)) continue;
                const double rest = g.restLength(di, dj);
                const double len = glm::length(state.positions[g.index(i + di, j + dj)] -
                                               state.positions[g.index(i, j)]);
                strain = std::max(strain, (len - rest) / rest);
            }
        }
    }
    return scene.springs.structural > 0 ? strain : 0;
}

bool allFinite(const SimState& state) {
    for (size_t k = 0; k < state.positions.size(); ++k) {
        const glm::dvec3 &p = state.positions[k], &v = state.velocities[k];
        if (!std::isfinite(p.x + p.y + p.z + v.x + v.y + v.z)) return false;
    }
    return true;
}

}  // namespace cloth
