// A cloth of a material (DESIGN.md §2 "Mass", the physical form), built in code. The tests of
// the per-vertex masses, the per-slot stiffnesses and the damping rate share it.
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// 16×12 vertices on 1.2 × 0.66 m, so du = 0.08 m ≠ dv = 0.06 m and the structural springs along
// u and v differ; density 0.15 kg/m², stretch 5000 N/m, shear 500 N/m, air damping 0.1 1/s; the
// axes orthogonal and tilted, pinned at the two corners of its upper edge, gravity off-axis, a
// light wind (a pressure of 0.2 N/m²: a force on each vertex's share of the area, ¼ and ½ of an
// inner vertex's at the corners and edges, as its mass).
//
// Lumped, a corner weighs ρ du dv/4 = 0.18 g and its springs give it the largest λ_k/m_k, about
// 1.1e8 1/s², hence ω_max ≈ 1.05e4 1/s: Δt = 1e-4 s is inside symplectic Euler's, Verlet's and
// RK4's bounds (≈ 2/ω_max and more); explicit Euler needs c > ω²Δt, Δt < 1e-9 s, which no
// test can afford: its runs are short.
Scene materialScene(Method method, double dt = 1e-4);

// The same sheet without pins, wind or tilt of gravity: it falls rigidly (every vertex has the
// same drag rate c = airDamping) and its springs stay at rest.
Scene fallingMaterialScene(Method method, double airDamping, double dt = 1e-4);

// A falling sheet's state: the velocity of its centre of mass Σ m_k v_k / Σ m_k [m/s] and its
// part across gravity (x, z; gravity is along −y) [m/s], the largest |v_k − that velocity|
// [m/s], and the largest relative stretch of a modelled spring.
struct FallingSheet {
    glm::dvec3 velocity{0};
    double sideways = 0, spread = 0, strain = 0;
};
FallingSheet fallingSheet(const Scene& scene, const SimState& state);

// The masses a solver models, measured: `probe` is the scene with gravity 0 and a wind of
// pressure kProbeWind along the cloth's normal, by symplectic Euler. One step from rest gives
// vertex k the velocity Δt·K_w·A_k/m_k along the normal, A_k its share of the area (as lumped
// here, apart from Scene::windArea), whatever the springs (at rest they pull with 0, up to the
// rounding of the rest lengths: K ≈ 6e3 N/m times 1e-8 m in float, 1e-7 of a corner's 240 N)
// and the drag (v = 0). Pins are removed.
inline constexpr double kProbeWind = 2e5;  // [N/m²]: every vertex reaches 133 m/s after 1e-4 s
Scene massProbeScene(const Scene& scene);
// m_k = Δt·K_w·A_k/|v_k| from the state after that one step [kg].
std::vector<double> probedMasses(const Scene& probe, const SimState& afterOneStep);
// One step of `solver` (built on `probe`) from its state, which must be at rest: the masses it
// models [kg].
std::vector<double> stepMasses(Solver& solver, const Scene& probe);
// Expects masses `m` [kg] to be the probe's lumped shares of `density` [kg/m²] (corners ¼, edges
// ½ of a cell's ρ·du·dv), summing to density × area about the sheet's centroid, each to the
// relative `tolerance`.
void expectLumpedMasses(const Scene& probe, double density, const std::vector<double>& m,
                        double tolerance, const std::string& what);

// A flat sheet of cells × (3/4 cells) cells on 1 × 0.75 m of cotton, no gravity or pins, in a
// wind of pressure 10 N/m² at 60° from its normal (docs/physics.md "Wind").
Scene windSheetScene(int cells);
// After one symplectic step from rest: the sheet's momentum along its normal over the impulse
// Δt·P·area·cos 60° the whole area feels (1 for a pressure), and the largest relative
// difference of the vertices' speeds from their mean (0: every vertex accelerates alike).
struct WindImpulse {
    double ofPressure = 0, spread = 0;
};
WindImpulse windImpulse(const Scene& scene, const SimState& afterOneStep);

}  // namespace cloth
