// Runs of the shared contact scenes (support/contact_scenes.h) that more than one test measures
// (tests/cpu/implicit_contact_test.cpp, tests/cpu/vbd_contact_test.cpp, the translation's tests).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"
#include "solver/solver.h"
#include "support/contact_scenes.h"

namespace cloth::test {

// sheetOverSphere(friction, integrator) run for 1.5 s on the CPU in double: its vertices' mean
// height [m].
inline double meanHeightOnSphere(double friction, const Json& integrator) {
    const Scene s = parseScene(sheetOverSphere(friction, integrator).dump(), "test");
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    const StepResult r = solver->step(std::lround(1.5 / s.integrator.dt));
    EXPECT_FALSE(r.unstable) << r.reason;
    return meanOf(solver->read().positions).y;
}

// clothOnTiltedBox's sheet made stiff (springs of 100 N/m, shear 25) under vbd: 10 sweeps at
// Δt = 1/60, the translation's step after the first `translationSweeps` of them.
inline Scene stiffSheetOnSlope(double degrees, double friction, int translationSweeps) {
    Json j = clothOnTiltedBox(degrees, friction);
    j["springs"] = {{"structural", 100.0}, {"shear", 25.0}};
    j["integrator"] = {{"method", "vbd"},
                       {"dt", 1.0 / 60},
                       {"iterations", 10},
                       {"translation_sweeps", translationSweeps}};
    return parseScene(j.dump(), "stiff sheet on a slope (test)");
}

// The largest distance between the same vertex of `a` and `b` after `steps` steps of each, on
// the CPU in double on 1 thread [m]: two paths to the same converged step end together.
inline double farthestApartAfter(const Scene& a, const Scene& b, long steps) {
    auto x = makeCpuSolver(a, {Precision::Double, 1});
    auto y = makeCpuSolver(b, {Precision::Double, 1});
    EXPECT_FALSE(x->step(steps).unstable);
    EXPECT_FALSE(y->step(steps).unstable);
    const SimState p = x->read(), q = y->read();
    double most = 0;
    for (std::size_t k = 0; k < p.positions.size(); ++k)
        most = std::max(most, glm::length(p.positions[k] - q.positions[k]));
    return most;
}

// How far `solver`'s centre moves in 1 s of steps of dt [m].
inline double slideInOneSecond(Solver& solver, double dt) {
    const glm::dvec3 start = meanOf(solver.read().positions);
    const StepResult r = solver.step(std::lround(1.0 / dt));
    EXPECT_FALSE(r.unstable) << r.reason;
    return glm::length(meanOf(solver.read().positions) - start);
}

// The largest structural strain `solver` reaches in `seconds` of steps of dt, checked every
// 0.1 s, as the command line's run checks max_strain; a non-finite step counts as infinite.
inline double largestStrainOver(Solver& solver, const Scene& scene, double seconds) {
    const long every = std::max(1L, std::lround(0.1 / scene.integrator.dt));
    double most = 0;
    for (long done = 0; done * scene.integrator.dt < seconds - 1e-9; done += every) {
        if (solver.step(every).unstable) return INFINITY;
        most = std::max(most, largestStrain(scene, solver.read()).strain);
    }
    return most;
}

// Coulomb's block from rest on a slope of `degrees` after 1 s, as backward Euler steps it:
// v_{n+1} = (v_n + h a)/(1 + h c), a = g (sin θ − μ cos θ), c the drag rate [1/s] [m].
inline double coulombBlockSlide(double degrees, double friction, double drag, double dt) {
    const double t = degrees * 3.14159265358979323846 / 180, g = 9.81;
    const double a = g * (std::sin(t) - friction * std::cos(t));
    double v = 0, x = 0;
    for (long n = 0; n < std::lround(1.0 / dt); ++n) {
        v = (v + dt * a) / (1 + dt * drag);
        x += dt * v;
    }
    return x;
}

}  // namespace cloth::test
