// A material at rest under its own weight (docs/physics.md "Statics"): three static problems
// with closed forms or convergence laws, each a scene that a solver settles. Implicit Euler with
// a step of seconds is Newton's method on the static problem (the masses' M/Δt² is ~10⁻⁶ of the
// stiffness), so a few steps reach the equilibrium that the solver's own forces define.
#pragma once

#include <functional>

#include "model/scene.h"
#include "solver/solver.h"

namespace cloth {

// A cantilever: a strip of `cells` cells along u (x) and 2 across (z, square cells; with the
// bending energy's ν = 0 its width plays no part), horizontal, clamped by
// pinning its first two columns, cotton's density with bending stiffness `bend` [N·m]. Its
// free length L runs from the second pinned column to the tip.
Scene cantileverScene(int cells, double length, double bend);
double cantileverFreeLength(const Scene& scene);  // [m]
// δ = ρ g L⁴ / (8B): the small-deflection tip sag [m].
double cantileverBeamSag(const Scene& scene);
// The tip's drop below the clamp's plane, averaged over the tip column [m].
double cantileverTipSag(const Scene& scene, const SimState& state);
// The inextensible elastica under the same uniform weight (θ'' = −(q/B)(L − s)cos θ, θ(0) = 0,
// θ'(L) = 0, shot on θ'(0)): the large-deflection tip sag [m].
double cantileverElasticaSag(const Scene& scene);

// A strip hanging from its top row, `cells` cells long (1 m) and a eighth of that across:
// uniaxial tension growing from 0 at the free end to ρ g L at the top. Along u or along v
// (then the cells are 1.5 times as wide as long, du ≠ dv).
Scene hangingStripScene(int cells, bool alongV);
// ΔL = ρ g L² / (2Y): the elongation under its own weight in uniaxial stress [m].
double hangingStripElongation(const Scene& scene);
// The bottom row's drop below its rest height, averaged over the row [m].
double hangingStripStretch(const Scene& scene, const SimState& state);

// A 1 m square of cotton hanging in its own plane from two 0.25 m stretches of its top edge,
// one at each corner, on `cells`² cells.
Scene hangingSheetScene(int cells);
// The middle of the bottom edge: its drop below its rest height [m].
double hangingSheetSag(const Scene& scene, const SimState& state);

// Steps `solver` one at a time until no vertex moves more than `tolerance` [m] in a step, or
// `maxSteps`; the state reached and the last step's largest move.
struct Settled {
    SimState state;
    int steps = 0;
    double lastMove = 0;  // [m]
    long iterations = 0;  // implicit Euler's CG iterations, all steps
};
Settled settle(Solver& solver, double tolerance, int maxSteps);

}  // namespace cloth
