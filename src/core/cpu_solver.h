// The CPU backend: DESIGN.md §2 in float or double, threads over bands of vertex rows.
#pragma once

#include <atomic>
#include <memory>
#include <variant>
#include <vector>

#include "core/colliders.h"
#include "core/solver.h"
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
    struct Spring {  // one active entry of kSpringOffsets
        int di, dj;
        std::int64_t indexOffset;  // dj·nu + di
        T stiffness, restLength;
    };
    struct Band {  // a thread's vertices [begin, end) and what it found wrong
        std::int64_t begin, end;
        std::int64_t badVertex = -1;
        std::string reason;
    };

    struct GrabT {
        std::int64_t vertex;
        Vec3<T> target;
        T stiffness;
    };

    void takeParameters(const Scene& scene);
    void computeForces(std::int64_t begin, std::int64_t end);  // pass 1
    bool integrate(Band& band);                                // pass 2; false if unstable
    void runBand(Band& band, long n, long& taken);
    StepResult stepThreaded(long n);

    Grid grid_;
    Features features_;
    std::vector<Spring> springs_;
    std::vector<Vec3<T>> x_, v_, f_, pinPosition_;
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
