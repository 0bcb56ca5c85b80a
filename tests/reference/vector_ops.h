// The few 3-vector operations the reference needs, spelled out (no glm: it shares nothing with
// src/).
#pragma once

#include <cmath>

#include "reference/reference.h"

namespace ref {

inline V3 add(const V3& a, const V3& b) {
    return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
inline V3 sub(const V3& a, const V3& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline V3 scale(double s, const V3& a) {
    return {s * a[0], s * a[1], s * a[2]};
}
inline double dot(const V3& a, const V3& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const V3& a) {
    return std::sqrt(dot(a, a));
}
inline V3 cross(const V3& a, const V3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline V3 normalised(const V3& a) {
    return scale(1.0 / norm(a), a);
}
// w − n ⟨n, w⟩: w's part along the surface of unit normal n (w itself where n = 0).
inline V3 tangential(const V3& n, const V3& w) {
    return sub(w, scale(dot(n, w), n));
}

}  // namespace ref
