// A vertex that starts a step inside a collider (a collider enabled or thickened over the cloth,
// or a scene that starts so), in a scheme whose velocity is the step's displacement, v = (x −
// x_n)/h (vbd): the iterates' projection puts it out, and v then carries that position correction
// as depth/h. This takes the part of it beyond the collider's own normal motion back out of v, and
// no more than v's part away from the surface: a vertex the collider pushes moves with it, one at
// rest on it (inside by rounding) may still leave. shaders/compute/vbd_finish.comp is the GPU's
// copy.
#pragma once

#include <algorithm>

#include "model/grid.h"

namespace cloth {

// v for a vertex that started at x_n, given the colliders as collide(p, v) (the end-of-step
// response, at the step's pose) and the velocity of the surface that touches p last as
// surface(p).
template <typename T, typename Collide, typename Surface>
Vec3<T> withoutStartCorrection(const Vec3<T>& start, const Vec3<T>& v, T h, const Collide& collide,
                               const Surface& surface) {
    Vec3<T> q = start, w(0);
    collide(q, w);
    const Vec3<T> d = q - start;
    const T depth = glm::length(d);
    if (!(depth > T(0))) return v;
    const Vec3<T> n = d / depth, vc = surface(start);
    const T excess = depth / h - glm::dot(n, vc), away = glm::dot(n, v - vc);
    return v - std::min(std::max(excess, T(0)), std::max(away, T(0))) * n;
}

}  // namespace cloth
