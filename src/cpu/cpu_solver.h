// The CPU backend: DESIGN.md §2 in float or double, threads over bands of vertex rows, with the
// five integrators of docs/integrators.md. State is structure-of-arrays (cpu/cpu_soa.h); the
// force pass runs row by row through vectorised kernels (cpu/cpu_rows.h) picked for the CPU at
// run time, and explicit/symplectic Euler fuse forces and update in one sweep over the rows
// (docs/performance.md, "CPU: SIMD layout, vectorised gather, fused passes").
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <utility>
#include <variant>
#include <vector>

#include "cpu/cpu_aggregation.h"
#include "cpu/cpu_colliders.h"
#include "cpu/cpu_multigrid.h"
#include "cpu/cpu_rows.h"
#include "cpu/cpu_self_collision.h"
#include "cpu/cpu_soa.h"
#include "cpu/cpu_vbd_phases.h"
#include "cpu/spin_barrier.h"
#include "cpu/worker_pool.h"
#include "model/bending.h"
#include "model/implicit_system.h"
#include "model/pin_follow.h"
#include "model/stiffness.h"
#include "model/vbd_lane.h"
#include "solver/solver.h"
#include "solver/step_check.h"

namespace cloth {

// With step control, it is its own StepCheck (cpu_step_check.cpp): a copy of the state, measured
// in double as largestStretchGrowth does.
template <typename T>
class CpuSolver final : public Solver, private StepCheck {
public:
    // isa: which row kernels; Auto picks the CPU's best or CLOTH_CPU_ISA (cpu/cpu_rows.h).
    CpuSolver(const Scene& scene, int threads, CpuIsa isa = CpuIsa::Auto);

    StepResult step(long n) override;
    SimState read() const override;
    Features features() const override { return features_; }
    std::string name() const override;
    CpuIsa isa() const { return isa_; }
    // Bytes of the per-vertex arrays it holds (bench/bench_speed_model.h cpuBytesPerVertex models
    // them), and of the threads' scratch rows.
    std::size_t allocatedBytes() const;
    std::size_t scratchBytes() const;

    void write(const SimState& state) override;
    void setPinned(int i, int j, bool pinned) override;
    void setGrab(const std::optional<Grab>& grab) override;
    void setParameters(const Scene& scene) override;
    void setColliderDrag(int index, const glm::dvec3& offset, const glm::dvec3& velocity) override {
        colliders_.drag(index, {offset, velocity, time()});
    }
    SelfCollisionStats selfCollisionStats() const override { return self_.stats(); }
    std::vector<std::int64_t> selfContactVertices() const override {
        std::vector<std::int64_t> k;
        const std::vector<std::uint8_t>& in = self_.inContact();
        for (std::size_t i = 0; i < in.size(); ++i)
            if (in[i]) k.push_back(std::int64_t(i));
        return k;
    }
    StepCheck* stepCheck() override { return features_.stepControl ? this : nullptr; }

private:
    using Spring = StencilSpring<T>;
    // reduce() sums chunks of whole rows, about this many vertices, each in order, then the
    // chunks in order; bands start on chunk boundaries, so a dot product has the same bits for
    // any thread count.
    static constexpr std::int64_t kChunk = 1024;
    // A thread's rows [rowBegin, rowEnd) = vertices [begin, end), what it found wrong, and its
    // scratch rows. Cache-line aligned: no two threads write to one line of their bands.
    struct alignas(64) Band {
        std::int64_t begin = 0, end = 0;
        int rowBegin = 0, rowEnd = 0;
        std::int64_t badVertex = -1;
        std::string reason;
        void fail(std::int64_t k, std::string why) {
            badVertex = k;
            reason = std::move(why);
        }
        int reductions = 0;  // dot products taken so far: picks the partial-sum slot
        // Spring coefficients of the last 3 rows (row j in slot j % 3), one array of nu per
        // upward spring: each spring's sqrt and division are done once for its two ends.
        AlignedVector<T> coefficients;
        AlignedVector<T> dampingCoefficients;  // the same for the spring damping (when modelled)
        Soa3<T> force;                         // one row of forces (the fused Euler sweep)
    };
    // A spring of the offset table as the row pass sees it: "upward" springs (dj > 0, or dj = 0
    // and di > 0) have their coefficients computed; the others read those of their reverse.
    struct RowSpring {
        int di, dj;
        T stiffness, restLength;
        bool upward;
        int slot;             // the coefficient array of this spring's upward direction
        int table;            // its index in kSpringOffsets
        bool halvedOnBorder;  // model/stiffness.h StencilSpring
        T damping;            // βK [N·s/m] (StencilSpring::damping)
    };
    // The threads of one step(n) call: sync() is a barrier between passes (none when serial).
    struct Team {
        SpinBarrier* barrier = nullptr;
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
    void gatherForces(Band& band);  // pass 1: F(x) into f_ for the band's rows
    void gatherForcesScalar(std::int64_t begin, std::int64_t end);  // the same, vertex by vertex
    // The row pass: spring coefficients of rows rowBegin − 2 … rowEnd − 1 into the band's ring,
    // rowDone(j) after row j's are in; forceRow gathers row j's forces from the ring.
    template <typename RowDone>
    void sweepRows(Band& band, const RowDone& rowDone);
    void coefficientRow(Band& band, int j, bool gatherLater);
    // Rows two or more from the border, wide enough to have columns that are too: one gather.
    bool interiorRow(int j) const { return j >= 2 && j < grid_.nv - 2 && grid_.nu >= 5; }
    void forceRow(Band& band, int j, Row3<T> f);
    // The spring's coefficient (or, with `damping`, its damping coefficient) for the vertex at
    // column i of row j, in the band's ring.
    const T* coefficientAt(const Band& band, const RowSpring& s, int j, int i,
                           bool damping = false) const;
    bool stepEulerFused(Band& band, bool symplectic);
    bool reportFirstBad(Band& band, std::int64_t begin, std::int64_t end);
    // One step of the scene's integrator over this band's vertices; false if it went unstable.
    bool advance(Band& band, const Team& team, long stepNumber, bool& haveForces);
    bool stepEuler(Band& band, const Team& team, bool symplectic);
    bool stepVerlet(Band& band, const Team& team, bool& haveForces);
    bool stepRk4(Band& band, const Team& team);
    bool stepImplicit(Band& band, const Team& team, long stepNumber);
    // vbd (cpu_vbd.cpp): the step's start and initial guess, one colour's Newton steps, the
    // Chebyshev extrapolation after a sweep, each over this band's vertices.
    bool stepVbd(Band& band, const Team& team, long stepNumber);
    void vbdStart(const Band& band, const Team& team, long stepNumber);
    void vbdSweep(const Band& band, int colour, bool pushes);
    VbdRow<T> vbdRow();
    void vbdRunOffsets(VbdRow<T>& r, int i) const;
    // Vertex k's iterate, position x and displacement d = x − x_n, and its copy in phases.
    void vbdSet(std::int64_t k, const Vec3<T>& x, const Vec3<T>& d);
    void vbdVertex(std::int64_t k, int i, int j, bool pushes);
    void vbdMove(std::int64_t k, Vec3<T> x, Vec3<T> d, std::int64_t c, const VbdLane<T>& lane,
                 bool pushes);
    // The border's vertices through the batch kernel (cpu_vbd_border.cpp).
    void vbdBatchTake(VbdBatch<T>& batch) const;
    void vbdBorderRun(VbdBatch<T>& batch, const std::int64_t* vertices, int n, bool pushes);
    void vbdTouch(std::int64_t c, const Vec3<T>& x, const Vec3<T>& p,
                  const typename CpuColliders<T>::Surface& surface, const VbdLane<T>& hessian);
    void vbdCollideRun(std::int64_t first, std::int64_t at, const std::uint8_t* moved, int n,
                       const T* const* hessian, bool pushes);
    void vbdProject(Vec3<T>& x, Vec3<T>& d) const;
    void vbdFillPhases(const Band& band);
    bool vbdFinishRows(Band& band);  // (cpu_vbd_finish.cpp)
    // Vertex k's displacement d = x − x_n: kept in phases alone where the solver keeps phases.
    Vec3<T> vbdDisplacement(std::int64_t k) const {
        return phases_.active() ? phases_.d.get(phases_.at(k)) : displacement_.get(k);
    }
    // The unit push p − x of a Newton step's projection at contact slot c (0: none), kept where
    // a translation's step reads it: `pushes` in vbdSweep, vbdVertex, vbdCollideRun (stepVbd).
    void vbdPushed(std::int64_t c, const Vec3<T>& x, const Vec3<T>& p) {
        const Vec3<T> push = p - x;
        const T length = push == Vec3<T>(0) ? T(0) : glm::length(push);
        pushNormal_.set(c, length > T(0) ? push / length : Vec3<T>(0));
    }
    // Where vertex k's contact is kept (VbdContacts: in phases' order with phases).
    std::int64_t vbdContactAt(std::int64_t k) const { return phases_.active() ? phases_.at(k) : k; }
    void vbdAccelerate(const Band& band, double omega);  // (cpu_vbd_chebyshev.cpp)
    // The translation's Newton step (cpu_vbd_translation.cpp): its sums over row j into out
    // (gradient 3, Hessian 6, Σ m/h²), then the step on every free vertex.
    void vbdTranslationRow(int j, double* out) const;
    void vbdTranslate(const Band& band, const Team& team);
    void vbdShiftRow(int j, int i0, int i1, const Vec3<T>& t, double* own = nullptr);
    void vbdPhasesFromGrid(int j);  // row j's positions in phases from x_
    double vbdTranslationTerms(int i, int j, std::int64_t k, VbdLane<double>& a) const;
    // Whether free vertex k's own terms (contact slot at) are linear in its displacement: no
    // friction contact, not grabbed. Their weight m/h² + m c/h, the gradient's rate of change.
    bool vbdLinearOwn(std::int64_t k, std::int64_t at) const {
        return !(grab_ && grab_->vertex == k) &&
               !(vbdContacts_.active() && vbdContacts_.weight[std::size_t(at)] != T(0));
    }
    double vbdInertiaDrag(std::int64_t k) const {
        const double h = double(dt_t_), m = 1.0 / double(inverseMass_[std::size_t(k)]);
        return m / (h * h) + m * double(dampingRate_) / h;
    }
    // The translation's levels (integrator.translation_levels, cpu_vbd_levels.cpp): row j's own
    // sums, a block's sums over row j, and the steps of every level before the first sweep.
    void vbdLevelOwnRow(int j);
    void vbdBlockRow(int j, int i0, int i1, int j0, int j1, bool pinsNear, double* out) const;
    void vbdTranslateLevels(const Band& band, const Team& team);
    void vbdTakeParameters(const Scene& scene);  // sweeps, ρ, their storage
    // The end of every step: pins, colliders in scene order, then the instability check.
    bool finishStep(Band& band, std::int64_t k, Vec3<T> p, Vec3<T> v);
    void applyPin(std::int64_t k, Vec3<T>& p, Vec3<T>& v) const;
    void constrain(std::int64_t k, Vec3<T>& p, Vec3<T>& v);  // pins, then colliders
    bool checkStability(Band& band, std::int64_t k, const Vec3<T>& p, const Vec3<T>& v) const;
    void applyColliders(Vec3<T>& p, Vec3<T>& v) const;  // colliders in scene order
    [[gnu::cold, gnu::noinline]] void reportBad(Band& band, std::int64_t k, const Vec3<T>& p,
                                                T speed2) const;
    Vec3<T> acceleration(std::int64_t k, const Vec3<T>& v) const;
    // Σ over all vertices of one value per vertex, the same bits whatever the thread count:
    // fixed chunks summed in order.
    template <typename PerVertex>
    double reduce(Band& band, const Team& team, const PerVertex& value);
    // The same for N sums at once: value(k) returns a std::array<double, N>.
    template <int N, typename PerVertex>
    std::array<double, N> reduceN(Band& band, const Team& team, const PerVertex& value);
    // implicit_euler's system A at the current state (model/implicit_system.h).
    ImplicitSystem<T, Soa3<T>> system() const;

    bool fused() const;  // explicit/symplectic Euler on row kernels: forces and update in one sweep
    // The end of a fused step: the new positions (and, with spring damping, velocities) become
    // the state.
    void swapFused() noexcept {
        std::swap(x_, xNext_);
        if (features_.springDamping) std::swap(v_, vNext_);
    }
    StepResult stepThreaded(long n);

    Grid grid_;
    Features features_;
    std::vector<Spring> springs_;
    std::vector<RowSpring> rowSprings_;
    int upwardSprings_ = 0;
    int families_ = 0;  // bit f: family f is modelled (RowKernels::gather)
    Method method_;
    CpuIsa isa_;
    const RowKernels<T>* kernels_ = nullptr;  // null on the scalar path
    // x_, v_: the state. The fused Euler sweep writes the new positions into xNext_ (neighbours
    // still read the old ones) and the two swap at the end of the step; it needs no f_.
    // With spring damping the forces read the neighbours' velocities too: the sweep writes the
    // new ones into vNext_, which swaps with v_ likewise.
    Soa3<T> x_, v_, f_, xNext_, vNext_;
    std::vector<Vec3<T>> pinPosition_;
    std::vector<std::int64_t> pinList_;  // the pinned vertices, ascending
    // Pins that follow a collider (model/pin_follow.h), posed with the colliders; their velocity
    // per vertex, sized only when there are any (every other pin's is 0).
    std::vector<FollowPin> follows_;
    std::vector<Vec3<T>> pinVelocity_;
    Vec3<T> pinVelocity(std::int64_t k) const {
        return pinVelocity_.empty() ? Vec3<T>(0) : pinVelocity_[std::size_t(k)];
    }
    void takeFollowPins(const Scene& scene);      // (cpu_pins.cpp)
    bool samePins(const Scene& scene) const;      // the grid's pins and follows equal the scene's
    void poseFollowPins(double t) noexcept;       // at time t [s]; allocates nothing
    std::vector<Vec3<T>> x0_, v0_, sumX_, sumV_;  // rk4: the step's start and Σ k_i
    // implicit_euler: the CG's vectors (dv_ the last solution, the next one's first guess), the
    // preconditioner's output z_ and its inverted diagonal blocks.
    std::vector<Vec3<T>> dv_, r_, p_, ap_, z_;
    Preconditioner preconditioner_ = Preconditioner::None;
    std::vector<Sym3<T>> blockInverse_;
    // The contacts in the solve (model/solve_contact.h), per vertex; empty without colliders.
    std::vector<SolveContact<T>> contacts_;
    CpuMultigrid<T> multigrid_;  // the "multigrid" preconditioner's hierarchy
    // The "aggregation" preconditioner's hierarchy and its vectors in double: r, z, positions.
    Aggregation aggregation_;
    std::vector<double> aggregationR_, aggregationZ_, aggregationX_;
    void setupAggregation();
    void applyAggregation(const Band& band, const Team& team);
    CycleThreads cycleThreads(const Band& band, const Team& team) const {
        return {int(&band - bands_.data()), int(bands_.size()), team.barrier};
    }
    // vbd: the step's displacement d = x − x_n (the iterate with x_; at the step's start only
    // where the solver keeps phases, whose copy the sweeps move: vbdDisplacement), the inertial
    // target's
    // ŷ = y − x_n = h v_n + h² a_ext, the previous step's velocity v_{n−1} (the adaptive initial
    // guess), and with Chebyshev acceleration the displacements of iterates n − 1, n − 2 (where
    // the solver keeps phases, in phases' order: vbdContactAt).
    Soa3<T> displacement_, dBefore_, dBeforeLast_;
    std::vector<Vec3<T>> inertialStep_, vPrevious_;
    std::vector<T> bendingDiagonal_;  // W_kk per vertex (model/vbd_local.h), with bending only
    VbdPhases<T> phases_;             // what the row kernel reads (with row kernels)
    VbdContacts<T> vbdContacts_;      // with colliders
    int vbdIterations_ = 0;
    double chebyshevRho_ = 0;
    int translationSweeps_ = 0;
    std::vector<double> translationRows_;  // per row, vbdTranslationRow's 10 sums
    int translationLevels_ = 0;
    int translationLevelPasses_ = 1;       // the levels' passes a step (vbdLevelPassSweep)
    std::vector<double> blockRows_;        // per row and block column, vbdBlockRow's 10 sums
    std::vector<std::uint8_t> rowPinned_;  // per row: whether it holds a pin (the levels')
    // The levels' own sums per row and finest block column (vbd_sums::kOwn each), whether each
    // row has a vertex whose own terms are not linear, the finest block column of each column
    // (and the finest parts a side at nu).
    std::vector<double> ownRows_;
    std::vector<std::uint8_t> rowNonlinear_;
    std::vector<int> finestColumn_;
    int springReach_ = 2;  // the farthest a spring of the stencil reaches along u or v (1 or 2)
    // With colliders and translation sweeps: the unit push of each vertex's last Newton step's
    // projection (0: none), where its contact is kept (vbdContactAt).
    Soa3<T> pushNormal_;
    long vbdHistoryFrom_ = 2;          // the first step whose v_{n−1} is in vPrevious_ (1-based)
    std::vector<double> partials_[2];  // per chunk and sum, for reduce()
    std::int64_t chunk_ = kChunk;      // vertices per chunk: whole rows
    double tolerance_ = 0;
    int maxIterations_ = 0;
    bool forcesValid_ = false;  // verlet: f_ holds F(x) of the current state
    // 1/m_k [1/kg] per vertex (Scene::vertexMass), pinned ones included: a pin resets its
    // vertex after the update, whatever its mass.
    AlignedVector<T> inverseMass_;
    std::vector<std::uint8_t> pinned_;
    T dt_t_, dampingRate_, maxSpeed2_;  // dampingRate_: c [1/s], drag −c m_k v_k
    // K_w times Scene::windArea: [on the first or last column][on the first or last row].
    T windStrength_[2][2];
    T windStrengthAt(int i, int j) const {
        return windStrength_[i == 0 || i == grid_.nu - 1][j == 0 || j == grid_.nv - 1];
    }
    BendingWeights bending_;  // a material's bending energy (model/bending.h); inactive: none
    Vec3<T> gravity_, windDirection_;
    CpuColliders<T> colliders_;
    // Poses the moving colliders and the pins that follow them at the end of step `stepNumber`
    // (1-based), before it is taken.
    void poseColliders(long stepNumber) noexcept {
        const double t = Solver::timeAt(stepNumber);
        if (colliders_.anyMoving()) colliders_.pose(t);
        if (!follows_.empty()) poseFollowPins(t);
    }
    // Self-collision (cpu/cpu_self_collision.h) and the positions at the step's start it needs.
    CpuSelfCollision<T> self_;
    Soa3<T> selfStart_;
    // Thread t of `threads` (sync: their barrier).
    bool resolveSelfContacts(int t, int threads, const std::function<void()>& sync);
    double maxSpeed_;
    std::optional<GrabT> grab_;
    std::vector<Band> bands_;
    std::unique_ptr<WorkerPool> pool_;

    // After the state was replaced (write, restore): the time, a start without history (vbd's
    // v_{n−1}, implicit_euler's last solution, verlet's forces), no instability.
    void startAfresh(double time);
    // Step control (cpu_step_check.cpp, solver/step_check.h): the kept state and its time.
    void keep() override;
    double stretchGrowth() override;
    void restore() override;
    Soa3<T> keptX_, keptV_;
    double keptTime_ = 0;
};

extern template class CpuSolver<float>;
extern template class CpuSolver<double>;

}  // namespace cloth
