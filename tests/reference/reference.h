// A naive, obviously-correct double-precision implementation of the model of DESIGN.md §2,
// written from the specification alone and sharing no code with src/. It is the oracle the CPU
// and GPU backends are checked against (DESIGN.md §6): plain loops, plain arrays, no glm.
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
struct Collider {
    bool isSphere = false;
    Plane plane{};
    Sphere sphere{};
};

struct Params {
    int nu = 2, nv = 1;
    double sizeU = 1, sizeV = 1;                         // [m]
    V3 origin{0, 0, 0}, uAxis{1, 0, 0}, vAxis{0, 0, 1};  // the reference normalises the axes
    double mass = 1;                                     // per vertex [kg]
    double kStructural = 0, kShear = 0, kBend = 0;       // [N/m]; 0 = family not modelled
    double damping = 0;                                  // μ [N·s/m]
    V3 gravity{0, -9.81, 0};                             // [m/s²]
    std::vector<std::array<int, 2>> pins;                // may be negative: -1 = last index
    bool wind = false;
    V3 windDirection{1, 0, 0};
    double windStrength = 0;          // K_w [N]
    std::vector<Collider> colliders;  // applied in this order
    double dt = 1e-3;                 // [s]
    double maxSpeed = 1e4;            // [m/s]
};

class Simulation {
public:
    explicit Simulation(const Params& p);  // rest positions, zero velocities
    void step();                           // one explicit Euler step in the order of §2
    long steps() const { return steps_; }
    const std::vector<V3>& positions() const { return p_; }  // index k = j·nu + i
    const std::vector<V3>& velocities() const { return v_; }
    double kineticEnergy() const;  // Σ ½ m |v|² [J]
    double springEnergy() const;   // Σ over springs, each once, ½ K (|d| − L)² [J]
    double gravityEnergy() const;  // −Σ m ⟨g, p⟩ [J]
    bool finiteAndBelowMaxSpeed() const;

    // Energies of an arbitrary state on this cloth (e.g. a solver's), same formulas as above.
    double kineticEnergy(const std::vector<V3>& v) const;
    double springEnergy(const std::vector<V3>& p) const;
    double gravityEnergy(const std::vector<V3>& p) const;

private:
    V3 restPosition(int i, int j) const;
    double stiffness(int family) const;
    double restLength(int di, int dj) const;
    V3 springForces(int i, int j) const;
    V3 windForce(int i, int j) const;
    void applyColliders(V3& p, V3& v) const;

    Params prm_;
    double du_ = 0, dv_ = 0;
    V3 u_{}, vAxis_{}, wind_{};
    std::vector<bool> pinned_;
    std::vector<V3> p_, v_;
    long steps_ = 0;
};

}  // namespace ref
