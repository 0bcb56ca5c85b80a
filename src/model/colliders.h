// DESIGN.md §2's two collider shapes, in the solver's precision. Their response, and every other
// shape's, is model/collider_contact.h's.
#pragma once

#include "model/grid.h"

namespace cloth {

template <typename T>
struct PlaneT {
    Vec3<T> point, normal;  // unit normal
};
template <typename T>
struct SphereT {
    Vec3<T> center;
    T radius;
};

}  // namespace cloth
