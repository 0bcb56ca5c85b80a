#include "render/geometry.h"

#include <cmath>

#include "core/forces.h"

namespace cloth::render {

ClothIndices clothIndices(int nu, int nv) {
    ClothIndices c;
    if (nu == 1 || nv == 1) {
        c.lines = true;
        for (std::uint32_t k = 0; k < std::uint32_t(nu) * std::uint32_t(nv); ++k)
            c.indices.push_back(k);
        return c;
    }
    c.indices.reserve(std::size_t(nu - 1) * std::size_t(nv - 1) * 6);
    for (int j = 0; j + 1 < nv; ++j) {
        for (int i = 0; i + 1 < nu; ++i) {
            const std::uint32_t k = std::uint32_t(j) * std::uint32_t(nu) + std::uint32_t(i);
            const std::uint32_t right = k + 1, up = k + std::uint32_t(nu), diag = up + 1;
            c.indices.insert(c.indices.end(), {k, right, up, right, diag, up});
        }
    }
    return c;
}

bool packCloth(const SimState& state, std::vector<glm::vec4>& positions,
               std::vector<glm::vec4>& normals) {
    const std::size_t n = state.positions.size();
    positions.resize(n);
    normals.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const glm::dvec3& p = state.positions[k];
        if (!std::isfinite(p.x + p.y + p.z)) return false;
        positions[k] = glm::vec4(glm::vec3(p), 1.0f);
    }
    const int nu = state.nu, nv = state.nv;
    const auto at = [&](int i, int j) { return state.positions[std::size_t(j) * nu + i]; };
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i)
            normals[std::size_t(j) * nu + i] =
                glm::vec4(glm::vec3(vertexNormal<double>(nu, nv, i, j, at)), 0.0f);
    return true;
}

SphereMesh uvSphere(int slices, int stacks) {
    SphereMesh m;
    constexpr float kPi = 3.14159265358979f;
    for (int s = 0; s <= stacks; ++s) {
        const float theta = kPi * float(s) / float(stacks);  // 0 at +y
        for (int l = 0; l <= slices; ++l) {
            const float phi = 2 * kPi * float(l) / float(slices);
            m.positions.emplace_back(std::sin(theta) * std::cos(phi), std::cos(theta),
                                     -std::sin(theta) * std::sin(phi));
        }
    }
    const auto index = [&](int s, int l) { return std::uint32_t(s * (slices + 1) + l); };
    for (int s = 0; s < stacks; ++s) {
        for (int l = 0; l < slices; ++l) {
            const std::uint32_t a = index(s, l), b = index(s + 1, l), c = index(s + 1, l + 1),
                                d = index(s, l + 1);
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    }
    return m;
}

}  // namespace cloth::render
