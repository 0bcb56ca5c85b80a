// The drape's impact on the sphere run frame by frame, and what it did to the sheet: the step
// control's tests on both backends run it (solver/step_control.h).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "backends/solver_factory.h"
#include "scene/scene_loader.h"
#include "solver/diagnostics.h"

namespace cloth::test {

// scenes/drape.json at `cells`², stretch 1e6 N/m, implicit Euler at Δt = 1/60 with multigrid
// CG to 1e-6, `maxStepStrain` (0: no step control); max_strain lifted so a torn sheet runs on.
inline Scene stiffDrape(int cells, double maxStepStrain) {
    const std::string n = std::to_string(cells);
    Scene scene = loadScene(CLOTH_SOURCE_DIR "/scenes/drape.json",
                            {"cloth.resolution=[" + n + "," + n + "]", "material.stretch=1e6",
                             "integrator.method=\"implicit_euler\"", "integrator.dt=0.016667",
                             "integrator.preconditioner=\"multigrid\"", "integrator.tolerance=1e-6",
                             "integrator.max_iterations=1000", "max_strain=100"});
    scene.integrator.maxStepStrain = maxStepStrain;
    return scene;
}

struct ImpactRun {
    double largest = 0;  // the largest structural stretch at the end of any frame
    long iterations = 0;
    StepControlStats control;
    long firstSplitFrame = 0, lastSplitFrame = 0;  // 1-based; 0: none
};

inline ImpactRun runImpact(const Scene& scene, const BackendChoice& backend, int frames) {
    std::unique_ptr<Solver> solver = makeSolver(scene, backend);
    ImpactRun r;
    for (int frame = 1; frame <= frames; ++frame) {
        const long split = solver->stepControlStats().split;
        EXPECT_FALSE(solver->step(1).unstable) << "frame " << frame;
        r.largest = std::max(r.largest, maxStrain(scene, solver->read()));
        if (solver->stepControlStats().split > split) {
            if (r.firstSplitFrame == 0) r.firstSplitFrame = frame;
            r.lastSplitFrame = frame;
        }
    }
    r.iterations = solver->solveStats().iterations;
    r.control = solver->stepControlStats();
    return r;
}

}  // namespace cloth::test
