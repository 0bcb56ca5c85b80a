// The viewer's simulation, without any window: the parameters the panel edits, the solver it
// steps, backend switches that carry the state, pins, the grab spring, reset and instability.
// The panel, the keyboard and `view --set` all change parameters through applyParameters().
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "backends/solver_factory.h"
#include "model/collider_pose.h"
#include "model/scene.h"
#include "solver/solver.h"

namespace cloth::app {

// What the panel edits: the scene (every collider, also switched-off ones) and the switches.
struct ViewerParams {
    Scene scene;
    std::vector<bool> colliderOn;  // one per scene.colliders
    // The scene the solver runs: switched-off colliders removed, follow pins renumbered (one
    // whose collider is off becomes a still pin; keepColliders in model/pin_follow.h).
    Scene effective() const;
};

// Rolling diagnostics for the plots: one sample every kSampleSeconds of wall time.
struct ViewerHistory {
    static constexpr std::size_t kSamples = 150;
    static constexpr double kSampleSeconds = 0.1;
    std::vector<float> energy, maxStrain, stepMs;  // [J], [1], [ms per step]
    // implicit_euler's solves: CG iterations per step over the sample, log10 of the last final
    // |r|/|b| (empty for the other integrators).
    std::vector<float> iterations, residual;
    void push(float e, float strain, float ms);
    void pushSolve(float iterationsPerStep, float log10Residual);
};

class ViewerSession {
public:
    // Throws InputError for a bad scene, GpuUnavailable when the GPU backend cannot run.
    ViewerSession(const Scene& scene, const BackendChoice& backend);

    // The one way parameters change (panel, --set, tests). Throws InputError, changing nothing,
    // when a moving collider would outrun the tunnelling limit at the new Δt (the loader's
    // checkColliderMotionStep, model/collider_limits.h). A different grid (resolution, size,
    // placement) rebuilds the cloth at rest; parameters the solver can take live go to
    // setParameters(); anything else (a family or collider switched on or off) builds a new
    // solver of the same backend and carries the state into it.
    void applyParameters(const ViewerParams& params);
    const ViewerParams& params() const { return params_; }

    // Runs `substeps` steps unless paused (one frame's worth when stepOnce). Returns the steps
    // taken; stops at an instability, which is then reported by unstable()/instability().
    long advance(bool stepOnce = false);
    void setPaused(bool paused) { paused_ = paused; }
    bool paused() const { return paused_; }
    // Back to the rest state with the current parameters.
    void reset();
    // Another backend or precision, carrying positions, velocities, pins and the grab over.
    void setBackend(const BackendChoice& backend);
    const BackendChoice& backend() const { return backend_; }

    // Pins or releases vertex k = j·nu + i where it is now.
    void togglePin(std::int64_t k);
    void clearPins();
    std::vector<std::int64_t> pinnedVertices() const;
    // The grab spring to a point the user drags; release() lets go.
    void grab(std::int64_t k, const glm::dvec3& target);
    void release();
    const std::optional<Grab>& grabbed() const { return grab_; }

    // The collider drag (docs/viewer.md): collider c (params order) heads for the displacement
    // `target` so as to reach it at the end of the next frame (substeps·Δt of simulated time),
    // no faster than clampDragVelocity allows, through Solver::setColliderDrag. Throws
    // std::invalid_argument when the backend cannot drag (the GPU, for now) or c is off.
    void dragCollider(std::size_t c, const glm::dvec3& target);
    void releaseCollider(std::size_t c);  // velocity 0: it stays where it is
    // Collider c's drag (nullptr if never dragged since the last rebuild) and its displacement now.
    const ColliderDrag* colliderDrag(std::size_t c) const;
    glm::dvec3 colliderOffset(std::size_t c) const;
    // The drags by the solver's collider order (switched-off colliders left out), for drawing
    // and picking; and the params index of the solver's collider e.
    std::vector<ColliderDrag> effectiveDrags() const;
    std::size_t paramsIndex(std::size_t effective) const;
    int effectiveIndex(std::size_t c) const;  // in the solver's colliders; −1 when off

    Solver& solver() { return *solver_; }
    const Solver& solver() const { return *solver_; }
    bool unstable() const { return !instability_.empty(); }
    const std::string& instability() const { return instability_; }
    double simTime() const { return simTime_; }
    long totalSteps() const { return totalSteps_; }
    double lastStepSeconds() const { return lastStepSeconds_; }  // wall time of the last advance
    long lastSteps() const { return lastSteps_; }
    // Samples energy, strain and step time into history() (reads the state back).
    void sampleDiagnostics();
    const ViewerHistory& history() const { return history_; }
    // Counts solver rebuilds (tests check that live changes do not rebuild).
    int rebuilds() const { return rebuilds_; }

private:
    void rebuild();
    void replaceSolver(const Scene& effective, const BackendChoice& backend);
    double grabStiffness(std::int64_t k) const;  // for a grab of vertex k [N/m]

    // The drags where they are now, put on a new solver (whose clock starts again); throws like
    // setColliderDrag, before anything changed.
    std::vector<std::optional<ColliderDrag>> carryDrags(Solver& next) const;

    ViewerParams params_;
    std::vector<std::optional<ColliderDrag>> drags_;  // by params index; since: solver time
    BackendChoice backend_;
    std::unique_ptr<Solver> solver_;
    std::optional<Grab> grab_;
    bool paused_ = false;
    std::string instability_;
    double simTime_ = 0, lastStepSeconds_ = 0;
    long totalSteps_ = 0, lastSteps_ = 0;
    int rebuilds_ = 0;
    ViewerHistory history_;
    SolveStats sampledSolves_;  // the solver's counts at the last sample
};

// The drag velocity v [m/s] scaled down so that one step of Δt moves the collider at most
// maxColliderStepTravel(c) (docs/colliders.md §7: no vertex tunnels through it), its own
// motion's top speed (maxMotionSpeed) included.
glm::dvec3 clampDragVelocity(const glm::dvec3& v, const Collider& c, double dt);

// The step that fits the displayed frame (substeps × dt, kept) to the method, for the panel's
// button: one step a frame for vbd and for a method whose `bound` (stableDt) is infinite
// (implicit Euler), and for the others the fewest equal steps at most 0.9 of the bound where dt is
// past that. Nothing where the step fits already, where the bound is not positive (explicit Euler
// without damping), or where the frame or its steps leave integrator.dt's or .substeps' range.
struct FrameStep {
    double dt;
    int substeps;
};
std::optional<FrameStep> frameStep(const IntegratorSpec& in, double bound);

// True when the two scenes' clothes differ in grid (resolution, size, origin or axes).
bool gridDiffers(const Scene& a, const Scene& b);

// Pins of a grid mapped onto a grid of another resolution (proportionally, duplicates merged).
std::vector<Pin> remapPins(const std::vector<Pin>& pins, const ClothSpec& from,
                           const ClothSpec& to);

}  // namespace cloth::app
