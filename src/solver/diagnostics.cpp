#include "solver/diagnostics.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "model/bending.h"
#include "model/stiffness.h"

namespace cloth {

Energy energy(const Scene& scene, const SimState& state) {
    const Grid g = scene.grid();
    double stiffness[kSpringOffsets.size()];
    for (std::size_t s = 0; s < kSpringOffsets.size(); ++s)
        stiffness[s] =
            familyModelled(scene, kSpringOffsets[s].family) ? scene.slotStiffness(int(s)) : 0.0;
    Energy e;
    for (int j = 0; j < g.nv; ++j) {
        for (int i = 0; i < g.nu; ++i) {
            const auto k = g.index(i, j);
            const glm::dvec3& p = state.positions[k];
            const double m = scene.vertexMass(i, j);
            e.kinetic += 0.5 * m * glm::dot(state.velocities[k], state.velocities[k]);
            e.gravity -= m * glm::dot(scene.gravity, p);
            for (std::size_t s = 0; s < kSpringOffsets.size(); ++s) {
                const SpringOffset& o = kSpringOffsets[s];
                // Each spring once: only the offsets pointing "forward" in index order.
                if (o.dj < 0 || (o.dj == 0 && o.di < 0)) continue;
                if (stiffness[s] == 0 || !g.contains(i + o.di, j + o.dj)) continue;
                const double stretch =
                    glm::length(state.positions[g.index(i + o.di, j + o.dj)] - p) -
                    g.restLength(o.di, o.dj);
                const bool half = scene.material && o.family == Family::Structural &&
                                  onBorderLine(o.di, o.dj, i, j, g.nu, g.nv);
                e.spring += (half ? 0.25 : 0.5) * stiffness[s] * stretch * stretch;
            }
        }
    }
    const BendingWeights bending = bendingWeights(g, scene.bendingStiffness());
    if (bending.active())
        e.bending = bendingEnergy(
            bending, [&](int i, int j) { return state.positions[std::size_t(g.index(i, j))]; });
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
    return familyModelled(scene, Family::Structural) ? strain : 0;
}

SpringStrain largestStrain(const Scene& scene, const SimState& state) {
    const Grid g = scene.grid();
    SpringStrain worst;
    for (const SpringOffset& o : kSpringOffsets) {
        if (o.di < 0 || (o.di == 0 && o.dj < 0)) continue;  // each spring once
        if (!familyModelled(scene, o.family)) continue;
        const double rest = g.restLength(o.di, o.dj);
        for (int j = 0; j < g.nv; ++j)
            for (int i = 0; i < g.nu; ++i) {
                if (!g.contains(i + o.di, j + o.dj)) continue;
                const std::int64_t a = g.index(i, j), b = g.index(i + o.di, j + o.dj);
                const double len = glm::length(state.positions[b] - state.positions[a]);
                const double strain = std::abs(len - rest) / rest;
                if (std::isnan(strain)) return {strain, a, b};  // a NaN is the worst
                if (strain > worst.strain) worst = {strain, a, b};
            }
    }
    return worst;
}

SpringStrain largestStretchGrowth(const Scene& scene, const SimState& before,
                                  const SimState& after) {
    const Grid g = scene.grid();
    SpringStrain worst;
    if (!familyModelled(scene, Family::Structural)) return worst;
    for (auto [di, dj] : {std::pair{1, 0}, {0, 1}}) {
        const double rest = g.restLength(di, dj);
        for (int j = 0; j < g.nv; ++j)
            for (int i = 0; i < g.nu; ++i) {
                if (!g.contains(i + di, j + dj)) continue;
                const std::int64_t a = g.index(i, j), b = g.index(i + di, j + dj);
                const double was = glm::length(before.positions[b] - before.positions[a]);
                const double is = glm::length(after.positions[b] - after.positions[a]);
                if (!std::isfinite(was) || !std::isfinite(is))  // the worst, before or after
                    return {std::numeric_limits<double>::infinity(), a, b};
                const double growth = (std::max(is, rest) - std::max(was, rest)) / rest;
                if (growth > worst.strain) worst = {growth, a, b};
            }
    }
    return worst;
}

std::optional<std::string> strainBreach(const Scene& scene, const SimState& state) {
    const SpringStrain s = largestStrain(scene, state);
    if (s.strain <= scene.maxStrain) return std::nullopt;
    const int nu = scene.cloth.nu;
    char buf[160];
    std::snprintf(buf, sizeof buf, "strain %.3g > max_strain %g on the spring (%d, %d)-(%d, %d)",
                  s.strain, scene.maxStrain, int(s.a % nu), int(s.a / nu), int(s.b % nu),
                  int(s.b / nu));
    return std::string(buf);
}

bool allFinite(const SimState& state) {
    for (size_t k = 0; k < state.positions.size(); ++k) {
        const glm::dvec3 &p = state.positions[k], &v = state.velocities[k];
        if (!std::isfinite(p.x + p.y + p.z + v.x + v.y + v.z)) return false;
    }
    return true;
}

}  // namespace cloth
