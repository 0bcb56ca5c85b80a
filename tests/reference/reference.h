// A naive, obviously-correct double-precision implementation of the model of DESIGN.md §2 and of
// the five integrators of docs/integrators.md, written from those pages alone and sharing no code
// with src/. It is the oracle the CPU and GPU backends are checked against (DESIGN.md §6): plain
// loops, plain arrays, no glm.
#pragma once

#include <array>
#include <vector>

namespace ref {

using V3 = std::array<double, 3>;

struct Plane {
    V3 point, normal;  // the reference normalises the normal itself
};
struct Sphere {
    V3 center;
    double radius;  // [m]
};
// docs/colliders.md §1 (reference_colliders.cpp).
struct Box {
    V3 center, half;  // half extents [m]
    V3 axis;          // rotation axis (any length > 0)
    double degrees;   // rotation angle
};
struct Capsule {
    V3 a, b;
    double radius;
};
// Samples at origin + (i, j, k)·cell, index (k·ny + j)·nx + i.
struct Grid {
    V3 origin;
    double cell;
    std::array<int, 3> count;
    std::vector<double> values;
};

// docs/colliders.md §3: none, or a linear path, a rotation or an oscillation.
struct Motion {
    enum class Type { None, Linear, Rotation, Oscillation } type = Type::None;
    V3 velocity{0, 0, 0};                 // linear [m/s]
    V3 axis{0, 1, 0}, pivot{0, 0, 0};     // rotation, oscillation
    double degreesPerSecond = 0;          // rotation
    double amplitude = 0, frequency = 0;  // oscillation [m], [Hz]
    double phaseDegrees = 0;              // oscillation
};

struct Collider {
    enum class Shape { Plane, Sphere, Box, Capsule, Grid };
    bool isSphere = false;  // DESIGN.md §2's two shapes: isSphere picks between plane, sphere
    Plane plane{};
    Sphere sphere{};
    // docs/colliders.md: another shape (then `shape` says which), thickness, friction, motion.
    Shape shape = Shape::Plane;  // read only when `extended`
    bool extended = false;
    Box box{};
    Capsule capsule{};
    Grid grid{};
    V3 gridAxis{0, 0, 1}, gridTranslation{0, 0, 0};
    double gridDegrees = 0;
    double thickness = 0, friction = 0;
    Motion motion{};
};

// docs/integrators.md; ExplicitEuler is the seed's scheme of DESIGN.md §2. BackwardEuler is the
// nonlinear step that vbd converges to, solved by Newton's method.
enum class Method { ExplicitEuler, SymplecticEuler, Verlet, Rk4, ImplicitEuler, BackwardEuler };

struct Params {
    int nu = 2, nv = 1;
    double sizeU = 1, sizeV = 1;                         // [m]
    V3 origin{0, 0, 0}, uAxis{1, 0, 0}, vAxis{0, 0, 1};  // the reference normalises the axes
    double mass = 1;                                     // per vertex [kg]
    // DESIGN.md §2 "Mass", the physical form: with density > 0 the vertex masses are lumped from
    // the area instead of `mass`: each du × dv cell gives a quarter of its ρ·du·dv to each of its
    // four corners.
    double density = 0;                             // ρ [kg/m²]
    double kStructural = 0, kShear = 0, kBend = 0;  // [N/m]; 0 = family not modelled
    // A stiffness of its own for the springs along offset (di, dj) of the §2 table, in place of
    // its family's (a material's structural springs along u and along v differ).
    struct OffsetStiffness {
        int di, dj;
        double k;  // [N/m]; 0 = not modelled
    };
    std::vector<OffsetStiffness> offsetStiffness;
    // A material's structural spring is the sum of a half from each cell beside it (docs/physics.md
    // "Borders"): K·n/2 with n = 1 on a border line, 2 inside. Off: every spring has its K.
    bool cellShares = false;
    // A material's bending stiffness B [N·m] (docs/physics.md "Bending"): the quadratic energy of
    // second differences along u and v and a twist per cell; 0 = not modelled.
    double bend = 0;
    double damping = 0;      // μ [N·s/m]: the drag −μ v on every vertex
    double dampingRate = 0;  // c [1/s]: a material's air damping, the drag −c·m_k·v on vertex k
    // β [s]: a material's spring damping; each spring of stiffness K pulls its ends a, b
    // together along d̂ = (x_b − x_a)/|x_b − x_a| with β K ((v_b − v_a)·d̂) on a, the opposite
    // on b (docs/physics.md "Spring damping"). 0 = not modelled.
    double springDamping = 0;
    V3 gravity{0, -9.81, 0};               // [m/s²]
    std::vector<std::array<int, 2>> pins;  // may be negative: -1 = last index
    // Per pin (missing entries: -1): the index in `colliders` of the moving collider the pin
    // follows (docs/colliders.md §5: the collider's pose at t applied to the rest position), or
    // -1 for a pin held at its rest position.
    std::vector<int> pinFollow;
    bool wind = false;
    V3 windDirection{1, 0, 0};
    double windStrength = 0;          // K_w [N]; with density > 0 a pressure [N/m²]
    std::vector<Collider> colliders;  // applied in this order
    Method method = Method::ExplicitEuler;
    double dt = 1e-3;           // [s]
    double cgTolerance = 1e-5;  // implicit Euler: stop at |r| <= tolerance·|b|
    int cgMaxIterations = 200;  // implicit Euler: ... or after this many iterations
    double maxSpeed = 1e4;      // [m/s]
};

// implicit_euler's conjugate-gradient solves so far (all zero for the other methods).
struct CgStats {
    long solves = 0;
    long iterations = 0;       // summed over solves
    long misses = 0;           // solves stopped by cgMaxIterations with |r| > tolerance·|b|
    int lastIterations = 0;    // of the latest solve
    double lastResidual = 0;   // final |r|/|b| of the latest solve (0 when b = 0)
    double worstResidual = 0;  // largest final |r|/|b| of a miss
};

class Simulation {
public:
    explicit Simulation(const Params& p);  // rest positions, zero velocities
    void step();  // one step of prm.method, then pins, then colliders (docs/integrators.md)
    long steps() const { return steps_; }
    // Replaces positions and velocities (same vertex count); pins keep their rest positions.
    void setState(const std::vector<V3>& p, const std::vector<V3>& v);
    const CgStats& cgStats() const { return cg_; }
    const std::vector<V3>& positions() const { return p_; }  // index k = j·nu + i
    const std::vector<V3>& velocities() const { return v_; }
    double kineticEnergy() const;  // Σ ½ m_k |v_k|² [J]
    double springEnergy() const;   // Σ over springs, each once, ½ K (|d| − L)² [J]
    double bendingEnergy() const;  // the bending energy of `bend` [J]
    double gravityEnergy() const;  // −Σ m_k ⟨g, p_k⟩ [J]
    double mass(int k) const { return mass_[k]; }  // m_k [kg]
    bool finiteAndBelowMaxSpeed() const;

    // Spring + wind force on every vertex of an arbitrary state of this cloth [N] (F of §2).
    std::vector<V3> forces(const std::vector<V3>& p) const;
    bool isPinned(int k) const { return pinned_[k]; }
    // y = H w at positions x, H = −∂F/∂x of the springs with implicit_euler's clamp (docs/
    // integrators.md): (H w)_k = Σ_springs of k J_s (w_k − w_q), pinned rows and columns removed
    // (w is read as 0 at pinned vertices, y is 0 there). With `pinnedColumns`, w is read at
    // pinned vertices too: implicit Euler's right-hand side h H v_n, where a follow pin's
    // velocity moves its neighbours' springs (docs/colliders.md §5).
    std::vector<V3> hessianProduct(const std::vector<V3>& x, const std::vector<V3>& w,
                                   bool pinnedColumns = false) const;

    // Energies of an arbitrary state on this cloth (e.g. a solver's), same formulas as above.
    double kineticEnergy(const std::vector<V3>& v) const;
    double springEnergy(const std::vector<V3>& p) const;
    double gravityEnergy(const std::vector<V3>& p) const;

private:
    V3 restPosition(int i, int j) const;
    // K of the spring from (i, j) along offset (di, dj) of family `family` [N/m].
    double stiffness(int i, int j, int di, int dj, int family) const;
    double drag(int k) const;  // μ_k of the drag −μ_k v on vertex k [N·s/m]
    double restLength(int di, int dj) const;
    V3 springForces(const std::vector<V3>& p, int i, int j) const;
    // The spring damping of the field w at positions x, added into f: each spring once, its
    // force scattered to both ends (the solvers gather per vertex). Pinned entries of w are read
    // as they are (the caller zeroes them where they must not count).
    void addSpringDamping(const std::vector<V3>& x, const std::vector<V3>& w,
                          std::vector<V3>& f) const;
    // The bending force −∂E_b/∂w of the field w, added into f: each stencil scatters its gradient
    // to its members (the solvers gather; this is the same energy written the other way round).
    // Entries of w at pinned vertices read as 0 unless `pinnedColumns`.
    void addBending(const std::vector<V3>& w, std::vector<V3>& f, bool pinnedColumns = true) const;
    V3 windForce(const std::vector<V3>& p, int i, int j) const;
    void applyColliders(V3& p, V3& v) const;
    void applyCollider(const Collider& c, V3& p, V3& v) const;
    V3 surfaceVelocity(V3 p) const;
    double colliderTime_ = 0;  // the end of the step being taken [s]: where colliders are
    // a(x, v) = (F(x) + F_β(x, v) − μ_k v)/m_k + g on free vertices, 0 on pinned ones, F_β the
    // spring damping.
    std::vector<V3> accelerations(const std::vector<V3>& x, const std::vector<V3>& v) const;
    // Pins (x ← x_pin, v ← 0; a follow pin at its pose at colliderTime_, v ← v_c there), then
    // every collider in scene order, on every vertex.
    void pinAndCollide(std::vector<V3>& x, std::vector<V3>& v) const;
    void pin(std::vector<V3>& x, std::vector<V3>& v) const;

    // The five schemes of docs/integrators.md (reference_integrators.cpp).
    void stepExplicitEuler();
    void stepSymplecticEuler();
    void stepVerlet();
    void stepRk4();
    void stepImplicitEuler();
    void stepBackwardEuler();  // (reference_backward_euler.cpp)
    // Conjugate gradient on ((m_k + hμ_k) I + h² H(x)) dv = b from dv = `fixed`, filtered by the
    // contacts' normals (0: none) and zero at the held ones; records the solve in cg_.
    std::vector<V3> solveImplicitSystem(const std::vector<V3>& x, const std::vector<V3>& b,
                                        const std::vector<V3>& normal,
                                        const std::vector<bool>& held,
                                        const std::vector<V3>& fixed);
    std::vector<V3> systemProduct(const std::vector<V3>& x, const std::vector<V3>& w) const;
    V3 coulomb(const V3& pStar, const V3& n, const V3& slide, double approach) const;

    Params prm_;
    double du_ = 0, dv_ = 0;
    V3 u_{}, vAxis_{}, wind_{};
    std::vector<double> mass_;  // m_k [kg]
    std::vector<bool> pinned_;
    std::vector<int> follow_;  // per vertex: the collider a pinned vertex follows, or -1
    std::vector<V3> rest_;     // pinned vertices are held at their rest position (moved by
                               // the followed collider's motion for a follow pin)
    std::vector<V3> p_, v_;
    // implicit_euler's contacts, from step to step: 0 none, > 0 sliding with the last solve's
    // normal impulse J_n [kg m/s], < 0 held.
    std::vector<double> grip_;
    // verlet with spring damping: F(x_{n+1}, v_half) of the last step, which the next step's
    // first kick uses (as the solvers, which evaluate the forces once a step); empty: none yet.
    std::vector<V3> verletForces_;
    long steps_ = 0;
    CgStats cg_;
};

}  // namespace ref
