#include "render/geometry.h"

#include <cmath>
#include <numbers>

#include "model/forces.h"

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

LitMesh litMesh(const TriMesh& mesh, double creaseDegrees) {
    // Each face's normal scaled by twice its area, and the faces around each vertex.
    std::vector<glm::dvec3> faces;
    std::vector<std::vector<std::uint32_t>> around(mesh.vertices.size());
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        const auto& t = mesh.triangles[f];
        faces.push_back(glm::cross(mesh.vertices[t[1]] - mesh.vertices[t[0]],
                                   mesh.vertices[t[2]] - mesh.vertices[t[0]]));
        for (const std::uint32_t v : t) around[v].push_back(f);
    }
    const auto unit = [](const glm::dvec3& n) {
        const double len = glm::length(n);
        return len > 0 ? n / len : glm::dvec3(0);
    };
    const double cosCrease = std::cos(creaseDegrees * std::numbers::pi / 180);
    LitMesh out;
    for (std::uint32_t f = 0; f < mesh.triangles.size(); ++f) {
        const glm::dvec3 own = unit(faces[f]);
        for (const std::uint32_t v : mesh.triangles[f]) {
            // The area-weighted mean of the faces at v that meet this one at less than the crease.
            glm::dvec3 n(0);
            for (const std::uint32_t g : around[v])
                if (glm::dot(unit(faces[g]), own) >= cosCrease) n += faces[g];
            out.positions.emplace_back(mesh.vertices[v]);
            out.normals.emplace_back(unit(n));
        }
    }
    return out;
}

}  // namespace cloth::render
