// Where a box's normal is well defined: test points clear of the regions where n jumps or is
// ambiguous, so that two implementations of the box's (φ, n) can be compared there.
#pragma once

#include <algorithm>
#include <cmath>

#include "model/collider_shapes.h"

namespace cloth::test {

// Whether p is clear, by `margin`, of the box's medial surface (inside: the nearest face must be
// nearer by `margin` than the second nearest, and p off the box's mid-planes) and of the borders
// between its face, edge and corner regions (outside).
template <typename T>
bool clearOfBoxKinks(const BoxT<T>& b, const Vec3<T>& p, T margin) {
    const Vec3<T> q = glm::transpose(b.rotation) * (p - b.center);
    const Vec3<T> d = glm::abs(q) - b.halfExtents;
    if (glm::length(glm::max(d, Vec3<T>(0))) > 0)
        return glm::all(glm::greaterThan(glm::abs(d), Vec3<T>(margin)));
    T first = -INFINITY, second = -INFINITY;
    for (int a = 0; a < 3; ++a) {
        if (d[a] > first) {
            second = first;
            first = d[a];
        } else {
            second = std::max(second, d[a]);
        }
    }
    return first - second > margin && glm::all(glm::greaterThan(glm::abs(q), Vec3<T>(margin)));
}

}  // namespace cloth::test
