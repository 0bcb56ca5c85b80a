#include "python/simulation.h"

#include <cmath>

#include "app/backend_options.h"
#include "backends/solver_factory.h"
#include "model/errors.h"
#include "model/stability.h"
#include "scene/scene_loader.h"

namespace cloth::python {
namespace {

// The backend the options and the environment choose, as `run`'s flags and environment choose
// it (app/backend_options.h). The GPU library takes the process's settings once, before the
// first solver (solver_factory.h). An option's InputError becomes std::invalid_argument:
// Python's ValueError for an argument, where a scene's error is a SceneError.
BackendChoice choose(const Options& o) try {
    static bool configured = false;
    if (!configured) {
        configureBackends(app::gpuSetupFromEnvironment());
        configured = true;
    }
    BackendChoice choice = app::backendChoiceFromEnvironment();
    if (!o.backend.empty()) app::parseBackend("backend", o.backend, choice);
    if (!o.precision.empty()) choice.precision = app::parsePrecision("precision", o.precision);
    app::refuseGpuDouble(choice, !o.precision.empty());
    if (choice.automatic && choice.precision == Precision::Double && !o.precision.empty())
        choice = {Backend::Cpu, Precision::Double, choice.threads, choice.gpu, choice.isa, false};
    if (o.threads && *o.threads < 1)
        throw InputError("", "threads", "expected a count >= 1, got " + std::to_string(*o.threads));
    choice.threads = o.threads.value_or(0);  // 0: automatic, by the cloth's size
    return choice;
} catch (const InputError& e) {
    throw std::invalid_argument(e.key() + ": " + e.reason());
}

// The backends refuse a bad environment variable (README, "Environment": CLOTH_*) as they refuse
// a scene key, by an InputError naming it: here it is an argument's error, not the scene's.
std::unique_ptr<Solver> solverFor(const Scene& scene, BackendChoice choice) try {
    settleBackend(choice, scene, false);  // "auto": the GPU on a hardware device, else the CPU
    return makeSolver(scene, choice);
} catch (const InputError& e) {
    if (e.key().rfind("CLOTH_", 0) != 0) throw;
    throw std::invalid_argument(e.key() + ": " + e.reason());
}

}  // namespace

Unstable::Unstable(const Scene& scene, const StepResult& r, const std::string& solverName)
    : result(r),
      advice(instabilityAdvice(scene, r)),
      time(double(r.firstBadStep) * scene.integrator.dt),
      stableDt(cloth::stableDt(scene)),
      message(scene.source + ": " + describeInstability(scene, r) + "; " + advice.text + " [" +
              solverName + "]") {}

std::unique_ptr<Simulation> Simulation::load(const std::string& path, const Options& options) {
    const BackendChoice choice = choose(options);  // a bad option before a long load
    return std::unique_ptr<Simulation>(new Simulation(loadScene(path, options.sets), choice));
}

std::unique_ptr<Simulation> Simulation::parse(const std::string& text, const std::string& source,
                                              const Options& options) {
    const BackendChoice choice = choose(options);
    return std::unique_ptr<Simulation>(
        new Simulation(parseScene(text, source, options.sets), choice));
}

Simulation::Simulation(Scene scene, const BackendChoice& choice)
    : scene_(std::move(scene)), solver_(solverFor(scene_, choice)) {}

void Simulation::stepChunk(long n, long end) {
    StepResult r = solver_->step(n);
    if (!r.unstable && strainCheckDue(checked_, solver_->stepsDone(), end,
                                      strainCheckSteps(scene_.integrator.dt))) {
        if (auto strained = strainInstability(scene_, *solver_, checked_)) r = *strained;
        checked_ = solver_->stepsDone();
    }
    if (r.unstable) throw Unstable(scene_, r, solver_->name());
}

namespace {

void checkFinite(const std::vector<glm::dvec3>& rows, const char* what) {
    for (std::size_t k = 0; k < rows.size(); ++k)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(rows[k][c]))
                throw std::invalid_argument(std::string(what) + ": row " + std::to_string(k) +
                                            " is not finite (nothing non-finite enters a state)");
}

}  // namespace

void Simulation::setPositions(std::vector<glm::dvec3> positions) {
    checkFinite(positions, "positions");
    SimState s = solver_->read();
    s.positions = std::move(positions);
    solver_->write(s);
}

void Simulation::setVelocities(std::vector<glm::dvec3> velocities) {
    checkFinite(velocities, "velocities");
    SimState s = solver_->read();
    s.velocities = std::move(velocities);
    solver_->write(s);
}

void Simulation::setPinned(int i, int j, bool pinned) {
    const int nu = scene_.cloth.nu, nv = scene_.cloth.nv;
    const int ii = i < 0 ? i + nu : i, jj = j < 0 ? j + nv : j;
    if (ii < 0 || ii >= nu || jj < 0 || jj >= nv)
        throw std::out_of_range("vertex (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is outside the " + std::to_string(nu) + " x " +
                                std::to_string(nv) + " grid");
    solver_->setPinned(ii, jj, pinned);
}

}  // namespace cloth::python
