// A random 3-vector drawn in one order on every compiler. C++ leaves unspecified the order in
// which a call's arguments are evaluated: in V(d(g), d(g), d(g)) GCC draws z first and Clang x,
// so the same test saw other samples under each (and one tolerance, set on GCC's, failed under
// Clang; docs/performance.md, "CI time"). z is drawn first here: the samples the tests' tolerances
// were set on.
#pragma once

#include <glm/glm.hpp>

namespace cloth::test {

template <typename Distribution, typename Generator>
glm::vec<3, typename Distribution::result_type> drawVec3(Distribution& d, Generator& g) {
    const auto z = d(g);
    const auto y = d(g);
    const auto x = d(g);
    return {x, y, z};
}

}  // namespace cloth::test
