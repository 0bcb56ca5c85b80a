// The one interface both backends implement (DESIGN.md §1): step(n), read(), features().
#pragma once

#include <algorithm>
#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/scene.h"

namespace cloth {

class StepCheck;

enum class Backend { Cpu, Gpu };
enum class Precision { Float, Double };

const char* backendName(Backend b);
const char* precisionName(Precision p);

// State copied out of a solver, in double whatever the solver computes in.
struct SimState {
    int nu = 0, nv = 0;
    std::vector<glm::dvec3> positions;   // [m], index k = j·nu + i
    std::vector<glm::dvec3> velocities;  // [m/s]
    double time = 0;  // [s] the solver's time (Solver::time()): write() carries it on
};

// What step(n) did. A run is unstable at the first step after which a position or velocity is
// not finite or a speed exceeds max_speed (DESIGN.md §2); the solver stops there. A backend that
// checks only every few steps (the GPU) reports the range the first bad step lies in.
struct StepResult {
    long stepsTaken = 0;  // steps completed by this call
    bool unstable = false;
    long firstBadStep = 0;  // 1-based global step numbers bracketing the first bad step
    long lastBadStep = 0;
    std::string reason;  // e.g. "speed 1.2e+04 m/s > max_speed 1e+04 at vertex (3, 7)"
};

// The features a scene declares, which decide what a solver computes (and on the GPU, compiles).
struct Features {
    bool structural = false, shear = false, bend = false, wind = false;
    bool bending = false;  // a material's bending energy (model/bending.h), not the bend springs
    // A material: its structural springs on a border line have half the stiffness (model/grid.h
    // onBorderLine); the per-vertex form's are uniform.
    bool borderShares = false;
    // Damping along the springs (Scene::springDamping > 0 and some spring modelled).
    bool springDamping = false;
    int planes = 0, spheres = 0, boxes = 0, capsules = 0, meshes = 0;
    // Colliders with a thickness, friction or motion (docs/colliders.md §2–3).
    int contactExtras = 0;
    bool selfCollision = false;  // Scene::selfCollision (docs/physics.md "Self-collision")
    bool stepControl = false;    // integrator.max_step_strain > 0 (solver/step_control.h)
    static Features of(const Scene& scene);
    bool operator==(const Features&) const = default;
    std::string describe() const;  // "structural+shear+bend, wind, 1 plane, 1 sphere, 2 boxes"
};

// A spring from one vertex to a point the user drags (the viewer's grab): F = K (target − x).
struct Grab {
    std::int64_t vertex = 0;  // k = j·nu + i
    glm::dvec3 target{0};     // [m]
    double stiffness = 0;     // [N/m]
};

// implicit_euler's conjugate-gradient solves since the solver was made (all zero for the other
// integrators). A solve that reaches max_iterations is a miss: the step goes on with its last
// iterate, and callers report the misses.
struct SolveStats {
    long solves = 0;
    long iterations = 0;       // summed over solves
    int mostIterations = 0;    // in one solve
    long misses = 0;           // solves that did not reach the tolerance (either way below)
    long firstMissStep = 0;    // 1-based step of the first miss
    double worstResidual = 0;  // largest final |r|/|b| of a miss
    // Misses that broke down before max_iterations: p·A p ≤ 0 or a sum not finite, which A
    // being positive definite leaves to a non-finite state or preconditioner output.
    long breakdowns = 0;
    long firstBreakdownStep = 0;  // 1-based, 0: none
    // The last solve's (run --out-solves writes them step by step).
    int lastIterations = 0;
    double lastResidual = 0;  // final |r|/|b|
    bool lastConverged = true;

    // One solve of step `step` (1-based): its iterations, final |r|/|b|, whether it reached the
    // tolerance, and whether it broke down (stopped short of both).
    void record(long step, int taken, double residual, bool converged, bool brokeDown) {
        ++solves;
        iterations += taken;
        mostIterations = std::max(mostIterations, taken);
        lastIterations = taken;
        lastResidual = residual;
        lastConverged = converged;
        if (converged) return;
        if (misses++ == 0) firstMissStep = step;
        worstResidual = std::max(worstResidual, residual);
        if (brokeDown && breakdowns++ == 0) firstBreakdownStep = step;
    }
};

// Self-collision's work since the solver was made (docs/physics.md "Self-collision"); all zero
// when the scene does not model it.
struct SelfCollisionStats {
    long steps = 0;           // steps it resolved
    long substeps = 0;        // summed over steps
    int mostSubsteps = 0;     // in one step
    long stepsOverBound = 0;  // steps that needed more than the substep cap
    long iterations = 0;      // Jacobi iterations, summed
    long contacts = 0;        // contacts corrected, summed over iterations
    int lastContacts = 0;     // in the first iteration of the last step's last substep
};

// The step control's work since the solver was made (solver/step_control.h); all zero when the
// scene does not declare it.
struct StepControlStats {
    long split = 0;     // steps of the scene's Δt taken in two or more pieces
    long rejected = 0;  // tries thrown away, at every depth
    long substeps = 0;  // steps the backend took, kept ones only
    int deepest = 0;    // most halvings of one step: Δt / 2^deepest
};

// GL buffer names of a backend that keeps its state in GL buffers (vec4 per vertex, k = j·nu + i):
// the renderer binds them as vertex buffers and copies nothing. Valid in the context the solver
// was made in.
struct DrawBuffers {
    unsigned positions = 0, normals = 0;
};

// What a backend tells of how it runs, beside the physics: for the benches, `run` and the viewer.
struct DeviceReport {
    double secondsPerStep = 0;  // device time per step of the last step(n) [s]; 0: not measured
    std::string timing;         // how: "GL timer query", "wall clock"; "" when not measured
    std::size_t bytes = 0;      // device memory the solver holds [bytes]; 0: none beyond the host's
    std::string variant;   // the kernel variant, e.g. "16x16/global"; "" for one-variant backends
    std::string dispatch;  // "per-step" or "many-steps"; "" where it does not apply
};

// Seconds of one dispatch of a pass over the whole grid, alone, best of some repeats: what a step's
// time is made of. NaN for a pass the backend does not time or the scene does not compile.
struct PassTimes {
    double forces = 0, integrate = 0;
};

class Solver {
public:
    virtual ~Solver() = default;
    // Advances up to n steps with no round trip to the caller; stops at the first unstable step.
    virtual StepResult step(long n) = 0;
    virtual SimState read() const = 0;
    virtual Features features() const = 0;
    virtual std::string name() const = 0;  // "cpu double, 2 threads", "gpu float (llvmpipe)"

    // Interactive control (the viewer). Each takes effect from the next step.
    // Replaces positions and velocities (same grid) and sets the time to state.time: carries a
    // run across backends, moving colliders and follow pins where they were.
    virtual void write(const SimState& state) = 0;
    // Pins vertex (i, j) where it is now (zero velocity), or releases it.
    virtual void setPinned(int i, int j, bool pinned) = 0;
    // Adds the grab spring to the forces pass, or removes it (nullopt).
    virtual void setGrab(const std::optional<Grab>& grab) = 0;
    // Takes the scene's parameters (stiffnesses, damping, mass, gravity, wind, collider
    // placement, dt, max_speed) without rebuilding. The grid, pins and Features::of(scene)
    // must equal the solver's; otherwise it throws std::invalid_argument and the caller
    // builds a new solver (and write()s the state into it).
    virtual void setParameters(const Scene& scene) = 0;
    // The viewer's collider drag (docs/colliders.md §3): from the next step collider `index`
    // (scene order) is displaced by offset + velocity·(t − t_now) on top of its own motion, and
    // its surface moves at `velocity` more, so the contact carries the cloth. Offsets persist;
    // velocity 0 leaves it where it is.
    virtual void setColliderDrag(int index, const glm::dvec3& offset,
                                 const glm::dvec3& velocity) = 0;
    // Where the renderer draws the cloth from without a copy, or nullopt: it then read()s.
    virtual std::optional<DrawBuffers> drawBuffers() const { return std::nullopt; }
    virtual DeviceReport deviceReport() const { return {}; }
    // Times the forces and integrate passes alone (bench speed --pass-times); may change the state
    // as steps would. Backends without device passes report NaN.
    virtual PassTimes timePasses(int repeats);

    long stepsDone() const { return steps_; }
    // Steps done and the time back to 0.
    void resetStepCount() { steps_ = originStep_ = 0, timeOrigin_ = 0; }
    // The simulated time [s]: t₀ + (steps − step₀)·Δt, re-based when Δt changes, so that the
    // moving colliders, follow pins and drags posed by it go on continuously.
    double time() const { return timeAt(steps_); }
    const SolveStats& solveStats() const { return solveStats_; }
    virtual SelfCollisionStats selfCollisionStats() const { return {}; }
    virtual StepControlStats stepControlStats() const { return {}; }
    // The backend's StepCheck (solver/step_check.h) where the scene declares step control
    // (Features::stepControl), else null. It lives as long as the solver.
    virtual StepCheck* stepCheck() { return nullptr; }
    // The vertices k = j·nu + i in a self-contact in the last step (the viewer marks them).
    virtual std::vector<std::int64_t> selfContactVertices() const { return {}; }

protected:
    // The time at the end of step `step` (1-based): the poses of that step. Bit for bit
    // double(step)·Δt while Δt has not changed and no time was written.
    double timeAt(long step) const { return timeOrigin_ + double(step - originStep_) * dt_; }
    // Δt from the next step on; the time now stays where it is.
    void setStepDt(double dt) {
        if (dt == dt_) return;
        timeOrigin_ = time();
        originStep_ = steps_;
        dt_ = dt;
    }
    // The time now becomes t [s] (write()); the same time changes nothing, not even a bit.
    void setTime(double t) {
        if (t == time()) return;
        timeOrigin_ = t;
        originStep_ = steps_;
    }

    long steps_ = 0;
    SolveStats solveStats_;
    double dt_ = 0;

private:
    double timeOrigin_ = 0;  // [s] t₀, the time at step originStep_
    long originStep_ = 0;
};

}  // namespace cloth
