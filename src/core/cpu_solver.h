// The CPU backend: DESIGN.md §2 in float or double, threads over bands of vertex rows, with the
// five integrators of docs/integrators.md.
#pragma once

#include <atomic>
#include <barrier>
#include <memory>
#include <variant>
#include <vector>

#include "core/colliders.h"
#include "core/solver.h"
#include "core/stiffness.h"
#include "core/worker_pool.h"

namespace cloth {

template <typename T>
class CpuSolver final : public Solver {
public:
    CpuSolver(const Scene& scene, int threads);

    StepResult step(long n) override;
    SimState read() const override;
    Features features() const override { return features_; }
    std::string name() const override;

    void write(const SimState& state) override;
    void setPinned(int i, int j, bool pinned) override;
    void setGrab(const std::optional<Grab>& grab) override;
    void setParameters(const Scene& scene) override;

private:
    using Spring = StencilSpring<T>;
    // reduce() sums chunks of this many vertices, each in order, then the chunks in order; bands
    // start on chunk boundaries, so a dot product has the same bits for any thread count.
    static constexpr std::int64_t kChunk = 1024;
    struct Band {  // a thread's vertices [begin, end) and what it found wrong
        std::int64_t begin, end;
        std::int64_t badVertex = -1;
        std::string reason;
        int reductions = 0;  // dot products taken so far: picks the partial-sum slot
    };
    // The threads of one step(n) call: sync() is a barrier between passes (none when serial).
    struct Team {
        std::barrier<>* barrier = nullptr;
        void sync() const {
            if (barrier) barrier->arrive_and_wait();
        }
    };

    struct GrabT {
        std::int64_t vertex;
        Vec3<T> target;
        T stiffness;
    };

    void takeParameters(const Scene& scene);
    void computeForces(std::int64_t begin, std::int64_t end);  // pass 1: F(x) into f_
    // One step of the scene's integrator over this band's vertices; false if it went unstable.
    bool advance(Band& band, const Team& team, long stepNumber, bool& haveForces);
    bool stepEuler(Band& band, const Team& team, bool symplectic);
    bool stepVerlet(Band& band, const Team& team, bool& haveForces);
    bool stepRk4(Band& band, const Team& team);
    bool stepImplicit(Band& band, const Team& team, long stepNumber);
    // The end of every step: pins, colliders in scene order, then the instability check.
    bool finishVertex(Band& band, std::int64_t k, Vec3<T> p, Vec3<T> v);
    void constrainVertex(std::int64_t k, Vec3<T>& p, Vec3<T>& v);  // pins, then colliders
    [[gnu::cold, gnu::noinline]] void reportBad(Band& band, std::int64_t k, const Vec3<T>& p,
                                                T speed2) const;
    Vec3<T> acceleration(std::int64_t k, const Vec3<T>& v) const;
    // Σ over all vertices of one value per vertex, the same bits whatever the thread count:
    // fixed chunks summed in order.
    template <typename PerVertex>
    double reduce(Band& band, const Team& team, const PerVertex& value);
    void systemProduct(const Band& band, const std::vector<Vec3<T>>& p, std::vector<Vec3<T>>& out);
    void recordSolve(long stepNumber, int iterations, double residual, bool converged);
    StepResult stepThreaded(long n);

    Grid grid_;
    Features features_;
    std::vector<Spring> springs_;
    Method method_;
    std::vector<Vec3<T>> x_, v_, f_, pinPosition_;
    std::vector<Vec3<T>> x0_, v0_, sumX_, sumV_;  // rk4: the step's start and Σ k_i
    std::vector<Vec3<T>> dv_, r_, p_, ap_;        // implicit_euler: CG vectors
    std::vector<double> partials_[2];             // per chunk, for reduce()
    double tolerance_ = 0;
    int maxIterations_ = 0;
    bool forcesValid_ = false;  // verlet: f_ holds F(x) of the current state
    std::vector<T> inverseMass_;
    std::vector<std::uint8_t> pinned_;
    T dt_t_, damping_, maxSpeed2_, windStrength_;
    Vec3<T> gravity_, windDirection_;
    std::vector<std::variant<PlaneT<T>, SphereT<T>>> colliders_;
    double maxSpeed_;
    std::optional<GrabT> grab_;
    std::vector<Band> bands_;
    std::unique_ptr<WorkerPool> pool_;
};

extern template class CpuSolver<float>;
extern template class CpuSolver<double>;

}  // namespace cloth
