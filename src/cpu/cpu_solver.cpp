#include "cpu/cpu_solver.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "cpu/cpu_solver_vertex.h"
#include "model/forces.h"
#include "model/vbd_local.h"

namespace cloth {
namespace {

template <typename T>
Vec3<T> cast(const glm::dvec3& v) {
    return Vec3<T>(v);
}

// Vertices below this count run on one thread: a barrier costs more than their whole step.
constexpr std::int64_t kMinVerticesPerThread = 1024;
// Self-collision costs some 50 times a step's work per vertex (docs/performance.md): its
// scenes are threaded from a fiftieth of that count.
constexpr std::int64_t kSelfCollisionWork = 50;
// Implicit Euler's step is a solve, tens of passes over the grid: two threads take the cotton
// drape at 38² with the multigrid in 1.13 s for 120 steps against one's 1.77 (docs/performance.md,
// "The passes' barrier"). Its scenes are threaded from half the count.
constexpr std::int64_t kImplicitWork = 2;

int chooseThreads(int requested, std::int64_t vertices) {
    if (requested > 0) return requested;
    const int hw = std::max(1u, std::thread::hardware_concurrency());
    return int(std::clamp<std::int64_t>(vertices / kMinVerticesPerThread, 1, hw));
}

}  // namespace

template <typename T>
CpuSolver<T>::CpuSolver(const Scene& scene, int threads, CpuIsa isa)
    : grid_(scene.grid()), features_(Features::of(scene)), isa_(resolveCpuIsa(isa)) {
    if (isa_ != CpuIsa::Scalar) kernels_ = &rowKernels<T>(isa_);
    const std::int64_t n = grid_.count();
    const int nu = grid_.nu, nv = grid_.nv;
    x_.assign(n, Vec3<T>(0));
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) x_.set(grid_.index(i, j), cast<T>(grid_.restPosition(i, j)));
    v_.assign(n, Vec3<T>(0));
    pinned_.assign(n, 0);
    pinPosition_.assign(std::size_t(n), Vec3<T>(0));
    for (const Pin& p : scene.pins) setPinned(p.i, p.j, true);
    takeFollowPins(scene);
    method_ = scene.integrator.method;
    takeParameters(scene);
    if (fused()) {
        xNext_ = x_;
        if (features_.springDamping) vNext_ = v_;
    } else if (method_ != Method::Vbd) {  // vbd gathers no forces
        f_.assign(n, Vec3<T>(0));
    }
    if (method_ == Method::Rk4)
        for (auto* a : {&x0_, &v0_, &sumX_, &sumV_}) a->assign(n, Vec3<T>(0));
    if (method_ == Method::ImplicitEuler)
        for (auto* a : {&dv_, &r_, &p_, &ap_}) a->assign(n, Vec3<T>(0));
    if (method_ == Method::Vbd) {
        displacement_.assign(n, Vec3<T>(0));
        for (auto* a : {&inertialStep_, &vPrevious_}) a->assign(n, Vec3<T>(0));
        if (kernels_) {
            phases_.configure(nu, nv);
            phases_.sizeBendDiagonal(bendingDiagonal_.size());
        }
    }  // (its Chebyshev iterates are takeParameters': a new ρ may ask for them)
    // Bands of whole rows, on chunk boundaries (reduce()), so each row's sweep is one thread's.
    // (Self-collision's threads need bands: a chunk of at most a sixteenth of the rows.)
    const std::int64_t chunk = scene.selfCollision ? std::min(kChunk, n / 16) : kChunk;
    const int chunkRows = int(std::max<std::int64_t>(1, chunk / nu));
    chunk_ = std::int64_t(chunkRows) * nu;
    const int chunks = (nv + chunkRows - 1) / chunkRows;
    for (auto& p : partials_) p.assign(2 * std::size_t(chunks), 0.0);
    const std::int64_t work =
        n * (scene.selfCollision ? kSelfCollisionWork : 1) *
        (scene.integrator.method == Method::ImplicitEuler ? kImplicitWork : 1);
    const int t = int(std::min<std::int64_t>(chooseThreads(threads, work), chunks));
    bands_.resize(std::size_t(t));
    for (int b = 0; b < t; ++b) {
        Band& band = bands_[std::size_t(b)];
        band.rowBegin = std::min(nv, int(std::int64_t(chunks) * b / t) * chunkRows);
        band.rowEnd = std::min(nv, int(std::int64_t(chunks) * (b + 1) / t) * chunkRows);
        band.begin = std::int64_t(band.rowBegin) * nu;
        band.end = std::int64_t(band.rowEnd) * nu;
        if (kernels_) {
            band.coefficients.assign(std::size_t(3) * upwardSprings_ * std::size_t(nu), T(0));
            if (features_.springDamping) band.dampingCoefficients = band.coefficients;
            if (fused()) band.force.assign(nu, Vec3<T>(0));
        }
    }
    // The multigrid's lines are paired for the team that relaxes them, known only here.
    if (method_ == Method::ImplicitEuler && preconditioner_ == Preconditioner::Multigrid)
        multigrid_.configure(nu, nv, t);
    if (method_ == Method::ImplicitEuler && preconditioner_ == Preconditioner::Aggregation)
        multigrid_.configure(nu, nv, t, true);  // its fine stencil: the aggregation's fine grid
    pool_ = std::make_unique<WorkerPool>(t);
}

template <typename T>
bool CpuSolver<T>::fused() const {
    return kernels_ && (method_ == Method::ExplicitEuler || method_ == Method::SymplecticEuler);
}

// Everything a scene sets that leaves the grid, the pins and the features as they are.
template <typename T>
void CpuSolver<T>::takeParameters(const Scene& scene) {
    grid_ = scene.grid();
    Solver::setStepDt(scene.integrator.dt);
    springs_ = activeSprings<T>(scene);
    rowSprings_.clear();
    upwardSprings_ = families_ = 0;
    for (const Spring& sp : springs_) {
        const bool upward = sp.dj > 0 || (sp.dj == 0 && sp.di > 0);
        int table = 0;
        while (kSpringOffsets[table].di != sp.di || kSpringOffsets[table].dj != sp.dj) ++table;
        families_ |= 1 << int(kSpringOffsets[table].family);
        rowSprings_.push_back({sp.di, sp.dj, sp.stiffness, sp.restLength, upward,
                               upward ? upwardSprings_++ : -1, table, sp.halvedOnBorder,
                               sp.damping});
    }
    for (RowSpring& r : rowSprings_)  // a family's springs come in pairs ±(di, dj)
        for (const RowSpring& u : rowSprings_)
            if (!r.upward && u.upward && u.di == -r.di && u.dj == -r.dj) r.slot = u.slot;
    if (method_ == Method::ImplicitEuler) {  // the preconditioner's storage, once it is chosen
        preconditioner_ = scene.integrator.preconditioner;
        const std::size_t n = std::size_t(grid_.count());
        if (preconditioner_ != Preconditioner::None && z_.size() != n) {
            z_.assign(n, Vec3<T>(0));
            blockInverse_.assign(n, Sym3<T>{});
        }
        // (A constructor's team is not known yet: it configures the multigrid once it is.)
        if ((preconditioner_ == Preconditioner::Multigrid ||
             preconditioner_ == Preconditioner::Aggregation) &&
            !multigrid_.configured() && !bands_.empty())
            multigrid_.configure(grid_.nu, grid_.nv, int(bands_.size()),
                                 preconditioner_ == Preconditioner::Aggregation);
    }
    tolerance_ = scene.integrator.tolerance;
    maxIterations_ = scene.integrator.maxIterations;
    if (method_ == Method::Vbd) vbdTakeParameters(scene);
    forcesValid_ = false;
    // The masses of the scene as given: a new mass (the viewer's) rescales every vertex's.
    inverseMass_.resize(std::size_t(grid_.count()));
    for (int j = 0; j < grid_.nv; ++j)
        for (int i = 0; i < grid_.nu; ++i)
            inverseMass_[std::size_t(grid_.index(i, j))] = T(1.0 / scene.vertexMass(i, j));
    dt_t_ = T(scene.integrator.dt);
    dampingRate_ = T(scene.dampingRate());
    bending_ = bendingWeights(grid_, scene.bendingStiffness());
    bendingDiagonal_.clear();
    if (method_ == Method::Vbd && bending_.active())
        for (int j = 0; j < grid_.nv; ++j)
            for (int i = 0; i < grid_.nu; ++i)
                bendingDiagonal_.push_back(bendingDiagonal<T>(bending_, i, j));
    if (phases_.active()) phases_.sizeBendDiagonal(bendingDiagonal_.size());
    gravity_ = cast<T>(scene.gravity);
    maxSpeed_ = scene.maxSpeed;
    maxSpeed2_ = T(scene.maxSpeed * scene.maxSpeed);
    for (int column = 0; column < 2; ++column)  // a corner, an edge's, an inner vertex's area
        for (int row = 0; row < 2; ++row)
            windStrength_[column][row] =
                scene.wind ? T(scene.wind->strength * scene.windArea(column ? 0 : 1, row ? 0 : 1))
                           : T(0);
    windDirection_ = scene.wind ? cast<T>(scene.wind->direction) : Vec3<T>(0);
    colliders_.take(scene);
    // The contacts of implicit_euler's solve (with colliders) or of vbd's friction survive this.
    const std::size_t contacts = colliders_.empty() ? 0 : std::size_t(grid_.count());
    if (method_ == Method::ImplicitEuler && contacts_.size() != contacts)
        contacts_.assign(contacts, SolveContact<T>{});
    vbdContacts_.resize(vbdContactCount(scene));
    if (scene.selfCollision) {
        if (!self_.active()) {
            self_ = CpuSelfCollision<T>(grid_, *scene.selfCollision);
            selfStart_ = x_;
        }
        self_.setParameters(*scene.selfCollision);
    }
}

// Self-collision after a step (cpu/cpu_self_collision.h) from its start in selfStart_; false
// where the cloth lies collapsed onto itself, named as the first band's bad vertex.
template <typename T>
bool CpuSolver<T>::resolveSelfContacts(int t, int threads, const std::function<void()>& sync) {
    const std::function<void(Vec3<T>&)> collide = [this](Vec3<T>& p) {
        Vec3<T> v(0);
        colliders_.apply(p, v);
    };
    if (self_.resolve(selfStart_, x_, v_, inverseMass_, pinned_, dt_t_, collide, t, threads, sync))
        return true;
    if (t == 0) bands_[0].fail(self_.crowded(), self_.crowdedReason());
    return false;
}

template <typename T>
void CpuSolver<T>::setParameters(const Scene& scene) {
    if (scene.cloth.nu != grid_.nu || scene.cloth.nv != grid_.nv)
        throw std::invalid_argument("setParameters: the grid size differs; build a new solver");
    if (!(Features::of(scene) == features_))
        throw std::invalid_argument("setParameters: the features differ; build a new solver");
    if (scene.integrator.method != method_)
        throw std::invalid_argument("setParameters: the integrator differs; build a new solver");
    if (!samePins(scene))
        throw std::invalid_argument("setParameters: the pins differ; use setPinned");
    takeParameters(scene);
    follows_ = followPins(scene);  // the same vertices and colliders, the motions may differ
}

template <typename T>
void CpuSolver<T>::write(const SimState& state) {
    if (state.nu != grid_.nu || state.nv != grid_.nv ||
        std::int64_t(state.positions.size()) != x_.size() ||
        std::int64_t(state.velocities.size()) != v_.size())
        throw std::invalid_argument("write: the state is for another grid");
    for (std::int64_t k = 0; k < x_.size(); ++k) {
        x_.set(k, cast<T>(state.positions[std::size_t(k)]));
        v_.set(k, cast<T>(state.velocities[std::size_t(k)]));
        if (pinned_[k]) pinPosition_[k] = x_.get(k);  // a pin holds the vertex where it now is
    }
    startAfresh(state.time);
}

template <typename T>
void CpuSolver<T>::startAfresh(double time) {
    Solver::setTime(time);
    forcesValid_ = false;
    std::fill(dv_.begin(), dv_.end(), Vec3<T>(0));  // no last solution to start from
    std::fill(contacts_.begin(), contacts_.end(), SolveContact<T>{});  // nor grips
    vbdContacts_.clear();
    vbdHistoryFrom_ = steps_ + 2;         // the written velocities have no predecessor
    if (self_.active()) selfStart_ = x_;  // the next step starts from here
    for (Band& b : bands_) {              // a written state starts afresh, as on the GPU
        b.badVertex = -1;
        b.reason.clear();
    }
}

template <typename T>
void CpuSolver<T>::setGrab(const std::optional<Grab>& grab) {
    if (grab && (grab->vertex < 0 || grab->vertex >= grid_.count()))
        throw std::invalid_argument("setGrab: vertex outside the grid");
    if (grab)
        grab_ = GrabT{grab->vertex, cast<T>(grab->target), T(grab->stiffness)};
    else
        grab_.reset();
    forcesValid_ = false;
}

// Out of the hot loop: the message for the first bad vertex of a band.
template <typename T>
void CpuSolver<T>::reportBad(Band& band, std::int64_t k, const Vec3<T>& p, T speed2) const {
    char buf[160];
    const int i = int(k % grid_.nu), j = int(k / grid_.nu);
    if (!std::isfinite(p.x + p.y + p.z) || !std::isfinite(speed2))
        std::snprintf(buf, sizeof buf, "non-finite position or velocity at vertex (%d, %d)", i, j);
    else
        std::snprintf(buf, sizeof buf, "speed %.3g m/s > max_speed %g m/s at vertex (%d, %d)",
                      double(std::sqrt(speed2)), maxSpeed_, i, j);
    band.fail(k, buf);
}

template <typename T>
StepResult CpuSolver<T>::step(long n) {
    StepResult result;
    if (bands_.size() == 1) {
        Band& band = bands_[0];
        bool haveForces = forcesValid_;
        for (long s = 0; s < n; ++s) {
            ++result.stepsTaken;
            poseColliders(steps_ + s + 1);
            const bool ok = advance(band, Team{}, steps_ + s + 1, haveForces);
            if (fused()) swapFused();  // the fused sweep always completes its step
            if (!ok) break;
            if (self_.active() && !resolveSelfContacts(0, 1, [] {})) break;
            if (self_.active()) selfStart_ = x_;
        }
    } else {
        result = stepThreaded(n);
    }
    forcesValid_ = method_ == Method::Verlet && result.stepsTaken > 0;
    steps_ += result.stepsTaken;
    for (const Band& b : bands_) {  // bands are in vertex order: the first bad one is the lowest
        if (b.badVertex < 0) continue;
        result.unstable = true;
        result.firstBadStep = result.lastBadStep = steps_;
        result.reason = b.reason;
        forcesValid_ = false;
        break;
    }
    return result;
}

template <typename T>
StepResult CpuSolver<T>::stepThreaded(long n) {
    // Every vertex's update reads only its own force and the previous positions, and dot products
    // sum fixed chunks in order: the result is bit-identical to a serial run for any thread count.
    SpinBarrier sync(int(bands_.size()));
    const Team team{&sync};
    // The end of a step: once every band is done, the fused sweep's new positions become x_.
    // The moving colliders are posed for the next step there too, while every thread waits.
    long posed = steps_ + 1;
    poseColliders(posed);
    std::atomic<bool> bad{false};
    // Whether the threads stop after this step: decided once, in the step end's completion, so that
    // all read one answer (a fast thread may set `bad` in the next step before a slow one leaves).
    bool stop = false;
    // With self-collision the threads resolve the step's contacts between the two barriers,
    // with the colliders still at the step's pose; the second poses them for the next.
    const bool self = self_.active();
    auto swapPositions = [this, &posed, &bad, &stop, self]() noexcept {
        stop = bad.load(std::memory_order_relaxed);
        if (fused()) swapFused();
        if (!self) poseColliders(++posed);
    };
    auto selfDone = [this, &posed, &stop]() noexcept {
        stop = self_.crowded() >= 0;  // resolve() stopped: the cloth lies collapsed on itself
        selfStart_ = x_;
        poseColliders(++posed);
    };
    SpinBarrier stepEnd(int(bands_.size()), swapPositions);
    SpinBarrier selfEnd(int(bands_.size()), selfDone);
    const std::function<void()> selfSync = [&sync] { sync.arrive_and_wait(); };
    long taken = 0;
    const bool forcesValid = forcesValid_;
    pool_->run([&](int t) {
        Band& band = bands_[t];
        bool haveForces = forcesValid;
        long s = 0;
        while (s < n) {
            if (!advance(band, team, steps_ + s + 1, haveForces))
                bad.store(true, std::memory_order_relaxed);
            ++s;
            stepEnd.arrive_and_wait();
            if (stop) break;
            if (self) {
                resolveSelfContacts(t, int(bands_.size()), selfSync);
                selfEnd.arrive_and_wait();
                if (stop) break;
            }
        }
        if (t == 0) taken = s;
    });
    StepResult r;
    r.stepsTaken = taken;
    return r;
}

template <typename T>
SimState CpuSolver<T>::read() const {
    SimState s;
    s.nu = grid_.nu;
    s.nv = grid_.nv;
    s.positions.resize(std::size_t(x_.size()));
    s.velocities.resize(std::size_t(v_.size()));
    for (std::int64_t k = 0; k < x_.size(); ++k) {
        s.positions[std::size_t(k)] = x_.get(k);
        s.velocities[std::size_t(k)] = v_.get(k);
    }
    s.time = time();
    return s;
}

template <typename T>
std::size_t CpuSolver<T>::allocatedBytes() const {
    std::size_t vectors = 0;
    for (const Soa3<T>* a :
         {&x_, &v_, &f_, &xNext_, &vNext_, &displacement_, &pushNormal_, &dBefore_, &dBeforeLast_})
        vectors += std::size_t(a->size());
    for (const auto* a : {&pinPosition_, &pinVelocity_, &x0_, &v0_, &sumX_, &sumV_, &dv_, &r_, &p_,
                          &ap_, &z_, &inertialStep_, &vPrevious_})
        vectors += a->size();
    return vectors * sizeof(Vec3<T>) + blockInverse_.size() * sizeof(Sym3<T>) +
           contacts_.size() * sizeof(SolveContact<T>) + vbdContacts_.bytes() + phases_.bytes() +
           (inverseMass_.size() + bendingDiagonal_.size()) * sizeof(T) + pinned_.size();
}

template <typename T>
std::size_t CpuSolver<T>::scratchBytes() const {
    std::size_t bytes = 0;
    for (const Band& b : bands_)
        bytes += (b.coefficients.size() + b.dampingCoefficients.size() +
                  3 * std::size_t(b.force.size())) *
                 sizeof(T);
    return bytes;
}

template <typename T>
std::string CpuSolver<T>::name() const {
    const int t = int(bands_.size());
    return std::string("cpu ") + (sizeof(T) == 4 ? "float" : "double") + " " + cpuIsaName(isa_) +
           ", " + std::to_string(t) + (t == 1 ? " thread" : " threads");
}

template class CpuSolver<float>;
template class CpuSolver<double>;

}  // namespace cloth
