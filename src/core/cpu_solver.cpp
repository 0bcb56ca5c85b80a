#include "core/cpu_solver.h"

#include <barrier>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/forces.h"

namespace cloth {
namespace {

template <typename T>
Vec3<T> cast(const glm::dvec3& v) {
    return Vec3<T>(v);
}

// Vertices below this count run on one thread: a barrier costs more than their whole step.
constexpr std::int64_t kMinVerticesPerThread = 4096;

int chooseThreads(int requested, std::int64_t vertices) {
    if (requested > 0) return requested;
    const int hw = std::max(1u, std::thread::hardware_concurrency());
    return int(std::clamp<std::int64_t>(vertices / kMinVerticesPerThread, 1, hw));
}

}  // namespace

template <typename T>
CpuSolver<T>::CpuSolver(const Scene& scene, int threads)
    : grid_(scene.grid()), features_(Features::of(scene)) {
    const std::int64_t n = grid_.count();
    x_.resize(n);
    for (int j = 0; j < grid_.nv; ++j)
        for (int i = 0; i < grid_.nu; ++i)
            x_[grid_.index(i, j)] = cast<T>(grid_.restPosition(i, j));
    v_.assign(n, Vec3<T>(0));
    f_.assign(n, Vec3<T>(0));
    pinned_.assign(n, 0);
    pinPosition_ = x_;
    for (const Pin& p : scene.pins) pinned_[grid_.index(p.i, p.j)] = 1;
    takeParameters(scene);
    const int t = chooseThreads(threads, n);
    for (int b = 0; b < t; ++b) bands_.push_back(Band{n * b / t, n * (b + 1) / t, -1, {}});
    pool_ = std::make_unique<WorkerPool>(t);
}

// Everything a scene sets that leaves the grid, the pins and the features as they are.
template <typename T>
void CpuSolver<T>::takeParameters(const Scene& scene) {
    grid_ = scene.grid();
    Solver::dt_ = scene.integrator.dt;
    springs_.clear();
    for (const SpringOffset& o : kSpringOffsets) {
        const double k = scene.springs.of(o.family);
        if (k > 0)
            springs_.push_back({o.di, o.dj, std::int64_t(o.dj) * grid_.nu + o.di, T(k),
                                T(grid_.restLength(o.di, o.dj))});
    }
    inverseMass_.assign(grid_.count(), T(1.0 / scene.cloth.mass));
    dt_t_ = T(scene.integrator.dt);
    damping_ = T(scene.damping);
    gravity_ = cast<T>(scene.gravity);
    maxSpeed_ = scene.maxSpeed;
    maxSpeed2_ = T(scene.maxSpeed * scene.maxSpeed);
    windStrength_ = scene.wind ? T(scene.wind->strength) : T(0);
    windDirection_ = scene.wind ? cast<T>(scene.wind->direction) : Vec3<T>(0);
    colliders_.clear();
    for (const Collider& c : scene.colliders) {
        if (const Plane* p = std::get_if<Plane>(&c))
            colliders_.push_back(PlaneT<T>{cast<T>(p->point), cast<T>(p->normal)});
        else if (const Sphere* s = std::get_if<Sphere>(&c))
            colliders_.push_back(SphereT<T>{cast<T>(s->center), T(s->radius)});
    }
}

template <typename T>
void CpuSolver<T>::setParameters(const Scene& scene) {
    if (scene.cloth.nu != grid_.nu || scene.cloth.nv != grid_.nv)
        throw std::invalid_argument("setParameters: the grid size differs; build a new solver");
    if (!(Features::of(scene) == features_))
        throw std::invalid_argument("setParameters: the features differ; build a new solver");
    std::vector<std::uint8_t> pinned(grid_.count(), 0);
    for (const Pin& p : scene.pins) pinned[grid_.index(p.i, p.j)] = 1;
    if (pinned != pinned_)
        throw std::invalid_argument("setParameters: the pins differ; use setPinned");
    takeParameters(scene);
}

template <typename T>
void CpuSolver<T>::write(const SimState& state) {
    if (state.nu != grid_.nu || state.nv != grid_.nv || state.positions.size() != x_.size() ||
        state.velocities.size() != v_.size())
        throw std::invalid_argument("write: the state is for another grid");
    for (size_t k = 0; k < x_.size(); ++k) {
        x_[k] = cast<T>(state.positions[k]);
        v_[k] = cast<T>(state.velocities[k]);
        if (pinned_[k]) pinPosition_[k] = x_[k];  // a pin holds the vertex where it now is
    }
}

template <typename T>
void CpuSolver<T>::setPinned(int i, int j, bool pinned) {
    if (!grid_.contains(i, j)) throw std::invalid_argument("setPinned: vertex outside the grid");
    const std::int64_t k = grid_.index(i, j);
    pinned_[k] = pinned ? 1 : 0;
    pinPosition_[k] = x_[k];
    if (pinned) v_[k] = Vec3<T>(0);
}

template <typename T>
void CpuSolver<T>::setGrab(const std::optional<Grab>& grab) {
    if (grab && (grab->vertex < 0 || grab->vertex >= grid_.count()))
        throw std::invalid_argument("setGrab: vertex outside the grid");
    if (grab)
        grab_ = GrabT{grab->vertex, cast<T>(grab->target), T(grab->stiffness)};
    else
        grab_.reset();
}

// Pass 1: each vertex gathers its springs (one loop over the active offsets) and the wind.
// Vertices two or more away from every border have all their neighbours: they skip the bounds
// checks and address neighbours by a fixed index offset.
template <typename T>
void CpuSolver<T>::computeForces(std::int64_t begin, std::int64_t end) {
    const int nu = grid_.nu, nv = grid_.nv;
    auto at = [&](int i, int j) -> const Vec3<T>& { return x_[std::int64_t(j) * nu + i]; };
    int i = int(begin % nu), j = int(begin / nu);
    for (std::int64_t k = begin; k < end; ++k) {
        Vec3<T> f(0);
        const Vec3<T> p = x_[k];
        if (i >= 2 && i < nu - 2 && j >= 2 && j < nv - 2) {
            for (const Spring& s : springs_)
                f += springForce(p, x_[k + s.indexOffset], s.stiffness, s.restLength);
        } else {
            for (const Spring& s : springs_) {
                const int qi = i + s.di, qj = j + s.dj;
                if (qi < 0 || qi >= nu || qj < 0 || qj >= nv) continue;
                f += springForce(p, x_[k + s.indexOffset], s.stiffness, s.restLength);
            }
        }
        if (features_.wind)
            f += windForce(vertexNormal<T>(nu, nv, i, j, at), windDirection_, windStrength_);
        f_[k] = f;
        if (++i == nu) {
            i = 0;
            ++j;
        }
    }
    // The user's grab spring, F = K (target − x), part of F like any spring.
    if (grab_ && grab_->vertex >= begin && grab_->vertex < end)
        f_[grab_->vertex] += grabForce(x_[grab_->vertex], grab_->target, grab_->stiffness);
}

// Pass 2: the seed's explicit Euler (DESIGN.md §2, seed eq. (6)), then pins, then colliders in
// scene order, then the instability check.
template <typename T>
bool CpuSolver<T>::integrate(Band& band) {
    const T dt = dt_t_;
    for (std::int64_t k = band.begin; k < band.end; ++k) {
        Vec3<T> p = x_[k], v = v_[k];
        const Vec3<T> a = (f_[k] - damping_ * v) * inverseMass_[k] + gravity_;
        p += dt * v;  // the old velocity: the seed's scheme, not symplectic
        v += dt * a;
        if (pinned_[k]) {
            p = pinPosition_[k];
            v = Vec3<T>(0);
        }
        for (const auto& c : colliders_)
            std::visit([&](const auto& shape) { collide(shape, p, v); }, c);
        x_[k] = p;
        v_[k] = v;
        const T speed2 = glm::dot(v, v);
        const bool finite = std::isfinite(p.x + p.y + p.z) && std::isfinite(speed2);
        if (!finite || speed2 > maxSpeed2_) {
            char buf[160];
            const int i = int(k % grid_.nu), j = int(k / grid_.nu);
            if (!finite)
                std::snprintf(buf, sizeof buf, "non-finite position or velocity at vertex (%d, %d)",
                              i, j);
            else
                std::snprintf(buf, sizeof buf,
                              "speed %.3g m/s > max_speed %g m/s at vertex (%d, %d)",
                              double(std::sqrt(speed2)), maxSpeed_, i, j);
            band.badVertex = k;
            band.reason = buf;
            return false;  // the rest of the band is not advanced: the run stops at this step
        }
    }
    return true;
}

template <typename T>
StepResult CpuSolver<T>::step(long n) {
    StepResult result;
    if (bands_.size() == 1) {
        Band& band = bands_[0];
        for (long s = 0; s < n; ++s) {
            computeForces(band.begin, band.end);
            ++result.stepsTaken;
            if (!integrate(band)) break;
        }
    } else {
        result = stepThreaded(n);
    }
    steps_ += result.stepsTaken;
    for (const Band& b : bands_) {  // bands are in vertex order: the first bad one is the lowest
        if (b.badVertex < 0) continue;
        result.unstable = true;
        result.firstBadStep = result.lastBadStep = steps_;
        result.reason = b.reason;
        break;
    }
    return result;
}

template <typename T>
StepResult CpuSolver<T>::stepThreaded(long n) {
    // Every vertex's update reads only its own force and the previous positions, so the result
    // is bit-identical to a serial run whatever the number of threads.
    std::barrier sync(std::ptrdiff_t(bands_.size()));
    std::atomic<bool> bad{false};
    long taken = 0;
    pool_->run([&](int t) {
        Band& band = bands_[t];
        long s = 0;
        while (s < n) {
            computeForces(band.begin, band.end);
            sync.arrive_and_wait();
            if (!integrate(band)) bad.store(true, std::memory_order_relaxed);
            ++s;
            sync.arrive_and_wait();
            if (bad.load(std::memory_order_relaxed)) break;
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
    s.positions.assign(x_.begin(), x_.end());
    s.velocities.assign(v_.begin(), v_.end());
    return s;
}

template <typename T>
std::string CpuSolver<T>::name() const {
    const int t = int(bands_.size());
    return std::string("cpu ") + (sizeof(T) == 4 ? "float" : "double") + ", " + std::to_string(t) +
           (t == 1 ? " thread" : " threads");
}

template class CpuSolver<float>;
template class CpuSolver<double>;

}  // namespace cloth
