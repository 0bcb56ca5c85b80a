#include "viewer/viewer_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "model/collider_limits.h"
#include "model/collider_speed.h"
#include "model/pin_follow.h"
#include "model/stability.h"
#include "solver/diagnostics.h"
#include "solver/instability.h"

namespace cloth::app {
namespace {

std::int64_t vertexIndex(const Scene& s, const Pin& p) {
    return std::int64_t(p.j) * s.cloth.nu + p.i;
}

}  // namespace

Scene ViewerParams::effective() const {
    return keepColliders(scene, colliderOn);  // follow pins renumbered; a dropped one holds still
}

void ViewerHistory::push(float e, float strain, float ms) {
    for (auto [series, value] : {std::pair{&energy, e}, {&maxStrain, strain}, {&stepMs, ms}}) {
        if (series->size() == kSamples) series->erase(series->begin());
        series->push_back(value);
    }
}

void ViewerHistory::pushSolve(float iterationsPerStep, float log10Residual) {
    for (auto [series, value] :
         {std::pair{&iterations, iterationsPerStep}, {&residual, log10Residual}}) {
        if (series->size() == kSamples) series->erase(series->begin());
        series->push_back(value);
    }
}

bool gridDiffers(const Scene& a, const Scene& b) {
    const ClothSpec &x = a.cloth, &y = b.cloth;
    return x.nu != y.nu || x.nv != y.nv || x.size != y.size || x.origin != y.origin ||
           x.uAxis != y.uAxis || x.vAxis != y.vAxis;
}

std::vector<Pin> remapPins(const std::vector<Pin>& pins, const ClothSpec& from,
                           const ClothSpec& to) {
    const auto map = [](int i, int n0, int n1) {
        return n0 <= 1 ? 0 : int(std::lround(double(i) * (n1 - 1) / (n0 - 1)));
    };
    std::vector<Pin> out;
    for (const Pin& p : pins) {
        const Pin q{map(p.i, from.nu, to.nu), map(p.j, from.nv, to.nv)};
        const bool seen = std::any_of(out.begin(), out.end(),
                                      [&](const Pin& o) { return o.i == q.i && o.j == q.j; });
        if (!seen) out.push_back(q);
    }
    return out;
}

glm::dvec3 clampDragVelocity(const glm::dvec3& v, const Collider& c, double dt) {
    // The drag adds to the collider's own motion: in the worst case their speeds add up.
    const double own = c.motion ? maxMotionSpeed(c) : 0.0;
    const double limit = std::max(0.0, maxColliderStepTravel(c) / dt - own);
    const double speed = glm::length(v);
    if (!(speed > limit)) return v;
    return limit > 0 ? v * (limit / speed) : glm::dvec3(0);
}

ViewerSession::ViewerSession(const Scene& scene, const BackendChoice& backend) : backend_(backend) {
    params_.scene = scene;
    params_.colliderOn.assign(scene.colliders.size(), true);
    rebuild();
}

void ViewerSession::applyParameters(const ViewerParams& next) {
    ViewerParams p = next;
    p.colliderOn.resize(p.scene.colliders.size(), true);
    checkColliderMotionStep(p.scene, p.colliderOn);  // as the loader does; before any change
    const bool grid = gridDiffers(p.scene, params_.scene);
    if (grid) p.scene.pins = remapPins(params_.scene.pins, params_.scene.cloth, p.scene.cloth);
    params_ = std::move(p);
    drags_.resize(params_.scene.colliders.size());
    if (grid || unstable()) {
        rebuild();
        return;
    }
    const Scene effective = params_.effective();
    try {
        solver_->setParameters(effective);
    } catch (const std::invalid_argument&) {
        replaceSolver(effective, backend_);  // another variant (a family, a collider) is needed
    }
    if (grab_) grab(grab_->vertex, grab_->target);  // the grab spring's stiffness follows dt
}

long ViewerSession::advance(bool stepOnce) {
    lastSteps_ = 0;
    if (unstable() || (paused_ && !stepOnce)) return 0;
    const long n = std::max(1, params_.scene.integrator.substeps);
    const auto t0 = std::chrono::steady_clock::now();
    const StepResult r = solver_->step(n);
    lastStepSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    lastSteps_ = r.stepsTaken;
    totalSteps_ += r.stepsTaken;
    simTime_ += double(r.stepsTaken) * params_.scene.integrator.dt;
    if (r.unstable) {
        instability_ = "unstable at step " + std::to_string(totalSteps_) + ": " + r.reason + ". " +
                       instabilityAdvice(params_.effective(), r).text;
        grab_.reset();
    }
    return r.stepsTaken;
}

void ViewerSession::reset() {
    grab_.reset();
    rebuild();
}

void ViewerSession::setBackend(const BackendChoice& backend) {
    if (unstable()) {  // nothing finite to carry over: start again on the new backend
        backend_ = backend;
        rebuild();
        return;
    }
    replaceSolver(params_.effective(), backend);
}

void ViewerSession::replaceSolver(const Scene& effective, const BackendChoice& backend) {
    const SimState state = solver_->read();
    std::unique_ptr<Solver> next = makeSolver(effective, backend);  // may throw: keep the old
    next->write(state);  // the time too: moving colliders and follow pins go on from there
    for (const Pin& p : params_.scene.pins) next->setPinned(p.i, p.j, true);  // where they are
    drags_ = carryDrags(*next);
    solver_ = std::move(next);
    backend_ = backend;
    ++rebuilds_;
    if (grab_) solver_->setGrab(grab_);
}

void ViewerSession::rebuild() {
    solver_ = makeSolver(params_.effective(), backend_);
    drags_.assign(params_.scene.colliders.size(), std::nullopt);  // the colliders at rest too
    ++rebuilds_;
    instability_.clear();
    simTime_ = 0;
    totalSteps_ = 0;
    history_ = {};
    if (grab_) solver_->setGrab(grab_);
}

void ViewerSession::togglePin(std::int64_t k) {
    const int nu = params_.scene.cloth.nu;
    const Pin pin{int(k % nu), int(k / nu)};
    auto& pins = params_.scene.pins;
    const auto it = std::find_if(pins.begin(), pins.end(),
                                 [&](const Pin& p) { return p.i == pin.i && p.j == pin.j; });
    const bool pinned = it == pins.end();
    if (pinned)
        pins.push_back(pin);
    else
        pins.erase(it);
    solver_->setPinned(pin.i, pin.j, pinned);
}

void ViewerSession::clearPins() {
    for (const Pin& p : params_.scene.pins) solver_->setPinned(p.i, p.j, false);
    params_.scene.pins.clear();
}

std::vector<std::int64_t> ViewerSession::pinnedVertices() const {
    std::vector<std::int64_t> v;
    for (const Pin& p : params_.scene.pins) v.push_back(vertexIndex(params_.scene, p));
    return v;
}

double ViewerSession::grabStiffness(std::int64_t k) const {
    // The scene's integrator stays stable while ω²_max of M⁻¹H is below the ω² its Δt allows
    // (docs/stability.md): the grab spring adds K/m_k to vertex k's row, so take half of the
    // margin the scene leaves, times m_k, within [0.1, 2]·K_structural.
    const Scene s = params_.effective();
    double structural = 0;
    for (std::size_t slot = 0; slot < kSpringOffsets.size(); ++slot)
        if (kSpringOffsets[slot].family == Family::Structural)
            structural = std::max(structural, s.slotStiffness(int(slot)));
    const double stiffness = std::max(structural, 1.0);
    const Method method = s.integrator.method;
    const double c = s.dampingRate(), dt = s.integrator.dt;
    if (std::isinf(methodDt(method, 1e30, c))) return 2 * stiffness;  // unconditionally stable
    if (!(methodDt(method, 0, c) > dt)) return 0.1 * stiffness;       // no margin at all
    double lo = 0, hi = 1;  // bisection for the largest ω² with a stable Δt above dt
    while (methodDt(method, hi, c) > dt && hi < 1e30) hi *= 4;
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (methodDt(method, mid, c) > dt ? lo : hi) = mid;
    }
    const int nu = s.cloth.nu;
    const double mass = s.vertexMass(int(k % nu), int(k / nu));
    const double margin = (lo - estimateStability(s).omega2Max) * mass;
    return std::clamp(0.5 * margin, 0.1 * stiffness, 2.0 * stiffness);
}

void ViewerSession::grab(std::int64_t k, const glm::dvec3& target) {
    if (unstable()) return;
    grab_ = Grab{k, target, grabStiffness(k)};
    solver_->setGrab(grab_);
}

void ViewerSession::release() {
    grab_.reset();
    solver_->setGrab(std::nullopt);
}

int ViewerSession::effectiveIndex(std::size_t c) const {
    if (c >= params_.scene.colliders.size() ||
        (c < params_.colliderOn.size() && !params_.colliderOn[c]))
        return -1;
    int e = 0;
    for (std::size_t k = 0; k < c; ++k)
        e += k >= params_.colliderOn.size() || params_.colliderOn[k];
    return e;
}

std::size_t ViewerSession::paramsIndex(std::size_t effective) const {
    for (std::size_t c = 0; c < params_.scene.colliders.size(); ++c)
        if (effectiveIndex(c) == int(effective)) return c;
    throw std::invalid_argument("no collider " + std::to_string(effective) + " is on");
}

void ViewerSession::dragCollider(std::size_t c, const glm::dvec3& target) {
    const int e = effectiveIndex(c);
    if (e < 0) throw std::invalid_argument("collider " + std::to_string(c) + " is off");
    const IntegratorSpec& in = params_.scene.integrator;
    const glm::dvec3 now = colliderOffset(c);
    const double frame = std::max(1, in.substeps) * in.dt;  // the next frame's simulated time
    const glm::dvec3 v =
        clampDragVelocity((target - now) / frame, params_.scene.colliders[c], in.dt);
    solver_->setColliderDrag(e, now, v);
    drags_[c] = ColliderDrag{now, v, solver_->time()};
}

void ViewerSession::releaseCollider(std::size_t c) {
    const int e = effectiveIndex(c);
    if (e < 0 || !drags_[c]) return;
    const glm::dvec3 now = colliderOffset(c);
    solver_->setColliderDrag(e, now, glm::dvec3(0));
    drags_[c] = ColliderDrag{now, glm::dvec3(0), solver_->time()};
}

const ColliderDrag* ViewerSession::colliderDrag(std::size_t c) const {
    return c < drags_.size() && drags_[c] ? &*drags_[c] : nullptr;
}

glm::dvec3 ViewerSession::colliderOffset(std::size_t c) const {
    const ColliderDrag* d = colliderDrag(c);
    return d ? d->at(solver_->time()) : glm::dvec3(0);
}

std::vector<ColliderDrag> ViewerSession::effectiveDrags() const {
    std::vector<ColliderDrag> out;
    for (std::size_t c = 0; c < drags_.size(); ++c)
        if (effectiveIndex(c) >= 0) out.push_back(drags_[c].value_or(ColliderDrag{}));
    return out;
}

std::vector<std::optional<ColliderDrag>> ViewerSession::carryDrags(Solver& next) const {
    std::vector<std::optional<ColliderDrag>> carried = drags_;
    for (std::size_t c = 0; c < carried.size(); ++c) {
        if (!carried[c]) continue;
        const glm::dvec3 now = colliderOffset(c);
        carried[c] = ColliderDrag{now, carried[c]->velocity, next.time()};
        if (const int e = effectiveIndex(c); e >= 0)
            next.setColliderDrag(e, now, carried[c]->velocity);
    }
    return carried;
}

void ViewerSession::sampleDiagnostics() {
    if (unstable()) return;
    const SimState state = solver_->read();
    if (!allFinite(state)) return;  // never plot a non-finite number
    const Scene s = params_.effective();
    // DESIGN.md §2's strain check, on the state the plots sample anyway (every kSampleSeconds).
    if (const auto why = strainBreach(s, state)) {
        StepResult breach;
        breach.unstable = true;
        breach.reason = *why;
        instability_ = "unstable by step " + std::to_string(totalSteps_) + ": " + *why + ". " +
                       instabilityAdvice(s, breach).text;
        grab_.reset();
        return;
    }
    const double msPerStep = lastSteps_ > 0 ? 1e3 * lastStepSeconds_ / double(lastSteps_) : 0;
    history_.push(float(energy(s, state).total()), float(maxStrain(s, state)), float(msPerStep));
    // The solves since the last sample (a new solver starts its counts at 0).
    const SolveStats& now = solver_->solveStats();
    if (now.solves < sampledSolves_.solves) sampledSolves_ = SolveStats{};
    if (now.solves > sampledSolves_.solves)
        history_.pushSolve(float(now.iterations - sampledSolves_.iterations) /
                               float(now.solves - sampledSolves_.solves),
                           float(std::log10(std::max(now.lastResidual, 1e-30))));
    sampledSolves_ = now;
}

std::optional<FrameStep> frameStep(const IntegratorSpec& in, double bound) {
    const int substeps = std::max(1, in.substeps);
    const double frame = substeps * in.dt;
    if (in.method == Method::Vbd || std::isinf(bound)) {
        if (substeps == 1 || frame > 10) return std::nullopt;  // integrator.dt's range
        return FrameStep{frame, 1};
    }
    if (!(bound > 0) || in.dt <= 0.9 * bound) return std::nullopt;
    const double steps = std::ceil(frame / (0.9 * bound));
    if (!(steps <= 100000)) return std::nullopt;  // past integrator.substeps' range
    return FrameStep{frame / steps, int(steps)};
}

}  // namespace cloth::app
