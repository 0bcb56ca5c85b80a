// A cloth collapsed onto itself: every vertex of `state` moved to a point drawn uniformly in a
// ball of `radius` around `centre` (a fixed seed), at rest. No step of a self-collision that
// kept the thickness can come to it; a written state can (a script, a drag in the viewer). Its
// vertices are each in far more contacts than one vertex's sums hold (model/self_contact.h).
#pragma once

#include <cmath>
#include <random>

#include "solver/solver.h"

namespace cloth::test {

inline SimState collapsedCloth(SimState state, const glm::dvec3& centre, double radius) {
    std::mt19937 random(17);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (std::size_t k = 0; k < state.positions.size(); ++k) {
        glm::dvec3 p;
        do {
            p = {unit(random), unit(random), unit(random)};
        } while (glm::dot(p, p) > 1);
        state.positions[k] = centre + radius * p;
        state.velocities[k] = glm::dvec3(0);
    }
    return state;
}

}  // namespace cloth::test
