// How far a collider may move in one step without a vertex tunnelling through it
// (docs/colliders.md §7). The viewer clamps a collider drag with it; scene validation checks
// moving colliders against it.
#pragma once

#include <vector>

#include "model/scene.h"

namespace cloth {

// The largest travel per step [m], relative to the cloth, that cannot carry a vertex through the
// collider: a + h for a box of smallest half extent a (the slab bound of §7), R + h for a sphere,
// r + h for a capsule of radius r, and for a mesh half the smallest extent of the OBJ's bounding
// box (in its own frame) + h — exact for a box- or sphere-like mesh, too generous where the mesh
// has parts thinner than its bounds. A plane bounds a half-space and cannot be passed through:
// infinity. h is the collider's thickness.
double maxColliderStepTravel(const Collider& collider);

// maxColliderStepTravel(c) / (maxMotionSpeed(c)·Δt) (model/collider_speed.h): how many times the
// collider's own step fits in what it may travel per step; +∞ for a still collider or a plane.
double motionStepMargin(const Collider& c, double dt);

// The scene loader's "clamp motion" rule (docs/colliders.md §7): a moving collider whose surface
// may move further in one step of integrator.dt than maxColliderStepTravel is refused with an
// InputError naming `colliders[n].motion`, giving the speed, Δt, the limit, and the largest Δt
// and the largest speed that pass. Colliders whose `on` entry is false are skipped (missing
// entries: on), so the viewer can check the scene it runs with the panel's numbering.
void checkColliderMotionStep(const Scene& scene, const std::vector<bool>& on = {});

}  // namespace cloth
