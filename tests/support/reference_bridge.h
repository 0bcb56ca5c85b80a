// Carries a cloth::Scene over to the reference model and compares a solver's state with it.
#pragma once

#include <string>
#include <vector>

#include "model/scene.h"
#include "reference/reference.h"
#include "solver/solver.h"

namespace cloth {

// The same scene in the reference's terms (pins already resolved, axes already normalised).
ref::Params toReference(const Scene& scene);

// max over vertices of |p_solver − p_ref|, divided by `extent` (the cloth's rest extent).
double maxDeviationOverExtent(const SimState& s, const ref::Simulation& r, double extent);

// CLOTH_SOURCE_DIR "/scenes/" name ".json", loaded and validated.
Scene loadShippedScene(const std::string& name);

// The scene without self-collision: as the reference models it (it has none), and as the GPU
// tests compare it where its contacts' threshold decisions would part the backends
// (tests/cpu/self_collision_test.cpp and tests/gpu/gpu_self_collision_test.cpp test it).
inline Scene withoutSelfCollision(Scene scene) {
    scene.selfCollision.reset();
    return scene;
}

// The solver's state as reference vectors, e.g. to evaluate the reference's energies on it.
std::vector<ref::V3> toReferenceVectors(const std::vector<glm::dvec3>& v);

// Kinetic + spring + gravity energy of a solver's state, by the reference's formulas [J].
// `model` is a reference simulation of the same scene (only its parameters are used).
double totalEnergy(const ref::Simulation& model, const SimState& s);

}  // namespace cloth
