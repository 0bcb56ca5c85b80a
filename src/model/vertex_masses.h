// The vertex masses a solver models, as one array: Scene::vertexMass of every vertex.
#pragma once

#include <vector>

#include "model/scene.h"

namespace cloth {

// m_k [kg] for k = j·nu + i: cloth.mass everywhere in the per-vertex form, a material's lumped
// share of the area times its density otherwise (Scene::vertexMass).
inline std::vector<double> vertexMasses(const Scene& scene) {
    const Grid g = scene.grid();
    std::vector<double> m(std::size_t(g.count()));
    for (int j = 0; j < g.nv; ++j)
        for (int i = 0; i < g.nu; ++i) m[std::size_t(g.index(i, j))] = scene.vertexMass(i, j);
    return m;
}

}  // namespace cloth
