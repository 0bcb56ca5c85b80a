// `clothsim bench speed --features`: a scene with every feature compiled in but none of them
// changing the motion, to measure what the features a scene does not declare would cost
// (DESIGN.md §3: "A feature the scene does not declare costs nothing"). Header-only so that the
// tests check the inert scene in-process.
#pragma once

#include <algorithm>
#include <string>

#include "model/errors.h"
#include "model/scene.h"
#include "solver/solver.h"

namespace cloth::app {

// What --features times: the scene as declared, with every feature, or both.
enum class FeatureSet { Declared, All, Both };

inline FeatureSet parseFeatureSet(const std::string& flag, const std::string& value) {
    if (value == "declared") return FeatureSet::Declared;
    if (value == "all") return FeatureSet::All;
    if (value == "both") return FeatureSet::Both;
    throw InputError("command line", flag, "expected declared, all or both, got '" + value + "'");
}

// A stiffness or wind strength that is declared (Features::of counts only non-zero ones) but
// whose force, ≤ 1e-30 N, vanishes against any force of the scene (mg ≈ 1e-2 N in hanging) even
// in float, whose smallest normal is 1.2e-38.
inline constexpr double kInertStrength = 1e-30;

// Colliders this many cloth extents away from the rest positions: nothing reaches them.
inline constexpr double kInertDistance = 1e3;

// The scene plus inert instances of every feature it does not declare: spring families of
// stiffness kInertStrength, wind of strength kInertStrength, a plane kInertDistance extents
// below the cloth (along gravity) and a sphere as far above it. Every code path of both
// backends then runs (and on the GPU is compiled), and the motion is the declared scene's up to
// rounding.
inline Scene withInertFeatures(const Scene& scene) {
    Scene s = scene;
    const Features f = Features::of(scene);
    if (!f.structural) s.springs.structural = kInertStrength;
    if (!f.shear) s.springs.shear = kInertStrength;
    if (!f.bend) s.springs.bend = kInertStrength;
    if (!f.wind) s.wind = Wind{glm::dvec3(1, 0, 0), kInertStrength};
    const Grid grid = scene.grid();
    const double extent = std::max(grid.extent(), 1e-3);  // [m]
    const double g = glm::length(scene.gravity);
    const glm::dvec3 down = g > 0 ? scene.gravity / g : glm::dvec3(0, -1, 0);
    const glm::dvec3 centre =
        0.5 * (grid.restPosition(0, 0) + grid.restPosition(grid.nu - 1, grid.nv - 1));
    const glm::dvec3 far = kInertDistance * extent * down;
    if (f.planes == 0) s.colliders.push_back(Plane{centre + far, -down});
    if (f.spheres == 0) s.colliders.push_back(Sphere{centre - far, extent});
    s.name = scene.name + "+inert";
    return s;
}

}  // namespace cloth::app
