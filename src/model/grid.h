// The (u, v) grid of DESIGN.md §2: vertex (i, j) has index k = j·nu + i, i fastest.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>

namespace cloth {

template <typename T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

enum class Family { Structural, Shear, Bend };
inline constexpr int kFamilyCount = 3;

inline const char* familyName(Family f) {
    switch (f) {
        case Family::Structural:
            return "structural";
        case Family::Shear:
            return "shear";
        case Family::Bend:
            return "bend";
    }
    return "?";
}

// The 12 neighbours a vertex gathers from (DESIGN.md §2 table). The three families are one
// table, walked by one loop (the seed's Q10), on the CPU, in the reference and in the shader.
struct SpringOffset {
    int di, dj;
    Family family;
};
inline constexpr std::array<SpringOffset, 12> kSpringOffsets{{
    {1, 0, Family::Structural},
    {-1, 0, Family::Structural},
    {0, 1, Family::Structural},
    {0, -1, Family::Structural},
    {1, 1, Family::Shear},
    {-1, 1, Family::Shear},
    {1, -1, Family::Shear},
    {-1, -1, Family::Shear},
    {2, 0, Family::Bend},
    {-2, 0, Family::Bend},
    {0, 2, Family::Bend},
    {0, -2, Family::Bend},
}};

// A material's structural spring along a border, both of whose ends lie on the first or last row
// (a spring along u) or column (along v), stands for the half cell of cloth beside it, not the
// two halves an inner one has: its stiffness is halved (docs/physics.md "Borders"). `di`, `dj`:
// a structural offset; (i, j): either end.
inline bool onBorderLine(int di, int dj, int i, int j, int nu, int nv) {
    return (dj == 0 && (j == 0 || j == nv - 1)) || (di == 0 && (i == 0 || i == nu - 1));
}

struct Grid {
    int nu = 2, nv = 1;
    double du = 0, dv = 0;  // spacing along û and v̂ [m]; 0 on a side of one vertex
    glm::dvec3 origin{0}, u{1, 0, 0}, v{0, 0, 1};  // û, v̂ unit vectors

    std::int64_t count() const { return std::int64_t(nu) * nv; }
    std::int64_t index(int i, int j) const { return std::int64_t(j) * nu + i; }
    bool contains(int i, int j) const { return i >= 0 && i < nu && j >= 0 && j < nv; }
    glm::dvec3 restPosition(int i, int j) const { return origin + i * du * u + j * dv * v; }
    // Rest length of the spring along offset (di, dj): |di·du·û + dj·dv·v̂|.
    double restLength(int di, int dj) const { return glm::length(di * du * u + dj * dv * v); }
    // Largest distance between two rest positions: the "cloth extent" errors are scaled by.
    double extent() const {
        const glm::dvec3 a = (nu - 1) * du * u, b = (nv - 1) * dv * v;
        return glm::max(glm::length(a + b), glm::length(a - b));
    }
};

}  // namespace cloth
