// The scene of `clothsim bench realtime`: the drape, built from a material preset at any
// resolution, and the per-vertex form that carries the same cloth uniformly.
#pragma once

#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth::app {

// An n × n sheet, 1 m × 1 m, horizontal at y = 0.8 m and centred above a sphere of radius 0.25 m
// resting on the ground plane y = 0 (its centre 0.25 m up); no pins; `material` a preset, the
// --set assignments `sets` applied on top (material.stretch=500, integrator.tolerance=1e-4, ...)
// and validated like a scene file. duration = `time`. Throws InputError naming the key (and the
// --set that gave it).
Scene realtimeDrape(const std::string& material, int n, double time,
                    const std::vector<std::string>& sets);

// The scene in the seed's per-vertex form: every vertex gets an interior vertex's mass ρ·du·dv,
// the structural and shear springs the material's membrane constants (the mean of u and v where
// the cells are not square), the drag μ = c·m; no bend springs and no bending energy. Border
// vertices are twice, corners four times as heavy as the material lumps them; otherwise the
// same membrane and drag: the seed's form of the cloth, beside which the material form shows what
// its lumped masses and bending change. A scene without a material is returned as it is.
Scene perVertexForm(const Scene& scene);

}  // namespace cloth::app
