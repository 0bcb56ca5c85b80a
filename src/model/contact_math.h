// The contact response's per-vertex arithmetic (docs/colliders.md §2) on plain scalars, as
// model/spring_math.h holds the springs': model/collider_contact.h's scalar response and the row
// kernels of every instruction set (cpu/isa/cpu_rows_isa.cpp) call this one function, so each
// lane computes the same operations in the same order and the results are bit-identical.
#pragma once

#include <cmath>

#include "model/spring_math.h"  // CLOTH_LANE

namespace cloth {

// The velocity part of the response on the components of one vertex in contact with unit normal
// n, against a collider whose surface moves at u = v_c there (model/collider_contact.h explains
// the law). Written without branches (every value computed, the result selected) so that the
// row kernels vectorise it. kFriction = (c_f > 0); without friction the tangential part is kept
// whole.
template <typename T, bool kFriction>
CLOTH_LANE void respondVelocityLane(T& vx, T& vy, T& vz, T nx, T ny, T nz, T ux, T uy, T uz,
                                    T friction) {
    const T wx = vx - ux, wy = vy - uy, wz = vz - uz;
    const T wn = (wx * nx + wy * ny) + wz * nz;  // glm::dot's order
    T ox = vx - wn * nx, oy = vy - wn * ny, oz = vz - wn * nz;
    if constexpr (kFriction) {
        const T tx = wx - wn * nx, ty = wy - wn * ny, tz = wz - wn * nz;
        const T slide = std::sqrt((tx * tx + ty * ty) + tz * tz);
        const T budget = friction * std::fabs(wn);  // the most speed friction can take
        const bool stick = slide <= budget;         // static: sliding would reverse
        const T k = budget / slide;
        ox = stick ? ux : ox - k * tx;
        oy = stick ? uy : oy - k * ty;
        oz = stick ? uz : oz - k * tz;
    }
    vx = ox;
    vy = oy;
    vz = oz;
}

}  // namespace cloth
