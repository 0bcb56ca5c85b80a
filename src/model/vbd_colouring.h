// The vertex colouring of Vertex Block Descent's Gauss–Seidel sweep (docs/integrators.md "vbd:
// the colouring"): vertices of one colour share no energy term, so a colour's vertices can take
// their local Newton steps in parallel.
#pragma once

namespace cloth {

inline constexpr int kVbdColours = 5;

// c(i, j) = (i + 2j) mod 5, for i, j ≥ 0. Every offset (di, dj) of the 12-neighbour stencil has
// di + 2dj ≢ 0 (mod 5), so two vertices joined by a spring, by a second difference of the
// bending energy or by a twist cell never share a colour.
constexpr int vbdColour(int i, int j) {
    return (i + 2 * j) % kVbdColours;
}

}  // namespace cloth
