// One trial of `clothsim bench realtime`: a scene at one size, stepped against the wall clock at
// the Δt its stability bound allows, halved after each instability.
#pragma once

#include "backends/solver_factory.h"
#include "bench/bench_realtime.h"

namespace cloth::app {

inline constexpr double kFrame = 1.0 / 60;  // one displayed frame [s]

// The first Δt a trial tries [s]: implicit Euler and vbd one frame; the others `safety` × their
// tight predicted bound `tightDt`, capped at one frame; 0 when no Δt is predicted stable.
double firstDt(Method method, double tightDt, double safety);

// Steps `scene` (its integrator and Δt = kFrame / stepsPerFrame set) on `choice` for `time`
// simulated seconds, in calls of step(n) within one frame each, timed by the steady clock (a
// GPU solver's step(n) returns when the device has finished: it waits with glFinish). The state
// at the end of every frame is checked against the scene's max_strain, off the clock. One warm-up
// step first, then the initial state written back: shader compilation, thread start and first
// touch of the arrays are set-up, not frames. Stopped as soon as the wall time passes
// kCutOffFactor × the simulated time + kCutOffSlack (CutOff), or at an instability; a completed
// run is also unstable when its final state breaks the scene's max_strain.
inline constexpr double kCutOffFactor = 1.5, kCutOffSlack = 0.05;
Trial timeTrial(const Scene& scene, const BackendChoice& choice, long stepsPerFrame, double time);

// The trial of `scene` (integrator method set) at its size: Δt = firstDt from the tight bound
// (model/stability.h, power iterations at the rest state), halved after an instability at most
// kMaxHalvings times. A run that is too slow or cut off is run once more at the same Δt and the
// faster of the two kept: the machine is shared, and another process's burst only ever slows a
// run down. DoesNotFit, without stepping, where the GPU cannot hold the grid.
inline constexpr int kMaxHalvings = 4;
Trial trialAtSize(Scene scene, const BackendChoice& choice, const RealtimeOptions& options);

}  // namespace cloth::app
