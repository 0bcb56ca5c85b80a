// What stands behind clothsim.Simulation, in C++ alone: a scene loaded as `clothsim run` loads it
// (the scene loader with --set overrides), a solver made for it by the backend factory, and
// steps taken by the run's rules (solver/instability.h). module.cpp binds it to Python.
#pragma once

#include <algorithm>
#include <exception>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "backends/solver_factory.h"
#include "model/scene.h"
#include "solver/diagnostics.h"
#include "solver/instability.h"
#include "solver/solver.h"

namespace cloth::python {

// The constructor's keywords, as their names; "" where not given.
struct Options {
    std::string backend, precision;
    std::optional<int> threads;
    // "KEY.PATH=JSON" assignments, applied in order as `run --set` applies them.
    std::vector<std::string> sets;
};

// A step went unstable (DESIGN.md §2): the solver's StepResult, or the strain check's, and the
// advice `clothsim run` prints with it.
class Unstable : public std::exception {
public:
    Unstable(const Scene& scene, const StepResult& r, const std::string& solverName);
    const char* what() const noexcept override { return message.c_str(); }

    StepResult result;
    InstabilityAdvice advice;
    double time = 0;      // [s] at the first bad step
    double stableDt = 0;  // [s] the predicted safe bound (model/stability.h stableDt)
    std::string message;  // as `clothsim run` says it on stderr
};

class Simulation {
public:
    // The scene file at `path`, or the JSON document `text` that `source` names in messages.
    // Throws InputError for the scene (its file, key path and reason), std::invalid_argument for
    // a bad option or environment variable, GpuUnavailable.
    static std::unique_ptr<Simulation> load(const std::string& path, const Options& options);
    static std::unique_ptr<Simulation> parse(const std::string& text, const std::string& source,
                                             const Options& options);

    // Advances n steps; throws Unstable at the first unstable one. `interrupted` is called
    // between runs of kStrainCheckSteps steps and throws to stop (Python's Ctrl+C).
    template <typename Interrupted>
    void step(long n, Interrupted interrupted);

    SimState state() const { return solver_->read(); }
    // Replaces the positions or the velocities (the solver's write(), as the viewer's backend
    // switch does). Throws std::invalid_argument for another count or a non-finite number.
    void setPositions(std::vector<glm::dvec3> positions);
    void setVelocities(std::vector<glm::dvec3> velocities);
    // (i, j) may count from the end, as the scene's pins do; std::out_of_range outside the grid.
    void setPinned(int i, int j, bool pinned);

    const Scene& scene() const { return scene_; }
    const Solver& solver() const { return *solver_; }

private:
    Simulation(Scene scene, const BackendChoice& choice);
    // Steps up to n (at most kStrainCheckSteps) of a call that ends at step `end`; throws Unstable.
    void stepChunk(long n, long end);

    Scene scene_;
    std::unique_ptr<Solver> solver_;
    long checked_ = 0;  // steps done at the last strain check
};

template <typename Interrupted>
void Simulation::step(long n, Interrupted interrupted) {
    if (n < 0)
        throw std::invalid_argument("n: expected a number of steps >= 0, got " + std::to_string(n));
    if (n > std::numeric_limits<long>::max() - solver_->stepsDone())
        throw std::invalid_argument("n: " + std::to_string(n) + " steps after " +
                                    std::to_string(solver_->stepsDone()) +
                                    " would count past 2^63 - 1");
    const long end = solver_->stepsDone() + n;
    while (solver_->stepsDone() < end) {
        stepChunk(std::min(strainCheckSteps(scene_.integrator.dt), end - solver_->stepsDone()),
                  end);
        interrupted();
    }
}

}  // namespace cloth::python
