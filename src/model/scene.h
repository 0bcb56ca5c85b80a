// A validated scene: what the simulation models, in SI units (DESIGN.md §4). Only what the file
// declares is here; a family of stiffness 0, an absent wind or an empty collider list is not
// modelled at all.
#pragma once

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "model/collider_motion.h"
#include "model/grid.h"

namespace cloth {

// The integrators of docs/integrators.md. explicit_euler is the seed's scheme (DESIGN.md §2).
enum class Method { ExplicitEuler, SymplecticEuler, Verlet, Rk4, ImplicitEuler, Vbd };

inline constexpr Method kMethods[] = {Method::ExplicitEuler, Method::SymplecticEuler,
                                      Method::Verlet,        Method::Rk4,
                                      Method::ImplicitEuler, Method::Vbd};

const char* methodName(Method m);  // "explicit_euler", ...
std::optional<Method> methodFromName(const std::string& name);
std::string methodList();  // "explicit_euler, symplectic_euler, ..."
// Spring-force passes one step costs (implicit_euler: + its CG; vbd: one per iteration).
int forceEvaluationsPerStep(Method m);

// implicit_euler's preconditioner of the conjugate gradient (docs/integrators.md,
// "Preconditioners"): none, the inverted 3×3 diagonal blocks of the system, one geometric
// multigrid V-cycle on the grid's hierarchy, or one V-cycle of adaptive smoothed aggregation,
// whose coarse spaces are built from the system at every step (the CPU backend only).
enum class Preconditioner { None, Jacobi, Multigrid, Aggregation };
inline constexpr Preconditioner kPreconditioners[] = {Preconditioner::None, Preconditioner::Jacobi,
                                                      Preconditioner::Multigrid,
                                                      Preconditioner::Aggregation};
// "none", "jacobi", "multigrid", "aggregation"
const char* preconditionerName(Preconditioner p);
std::optional<Preconditioner> preconditionerFromName(const std::string& name);

struct ClothSpec {
    int nu = 2, nv = 2;                         // vertices along u and v
    glm::dvec2 size{1, 1};                      // extent along û and v̂ [m]
    glm::dvec3 origin{0};                       // position of vertex (0, 0) [m]
    glm::dvec3 uAxis{1, 0, 0}, vAxis{0, 0, 1};  // normalised by the loader
    double mass = 1;                            // per vertex [kg]
};

struct SpringStiffness {
    double structural = 0, shear = 0, bend = 0;  // [N/m]; 0 = family not modelled
    double of(Family f) const;
};

// A fabric in SI units (docs/physics.md "Materials"), the alternative to the per-vertex form's
// cloth.mass, springs and damping. Mapped onto the grid by Scene's vertexMass, slotStiffness,
// dampingRate and bendingStiffness, so that a finer grid is the same cloth.
struct Material {
    std::string preset;        // the preset it started from, "" for none
    double density = 0;        // areal density ρ [kg/m²]
    double stretch = 0;        // membrane tensile stiffness Y: force per width per strain [N/m]
    double shear = 0;          // membrane shear stiffness G [N/m]
    double bend = 0;           // bending stiffness B: moment per width per curvature [N·m]
    double airDamping = 0;     // drag per unit mass c [1/s]: F = −c m v
    double springDamping = 0;  // damping along each spring, in units of its stiffness [s]
};

// The lattice's membrane constants for a material on cells du × dv (docs/physics.md): the
// stiffness of the structural springs along u and v and of the shear springs [N/m].
struct MembraneSprings {
    double alongU = 0, alongV = 0, shear = 0;
};
MembraneSprings membraneSprings(const Material& m, double du, double dv);

struct IntegratorSpec {
    Method method = Method::ExplicitEuler;
    double dt = 1e-3;  // [s]
    int substeps = 1;  // steps per displayed frame in the viewer
    // implicit_euler only: the conjugate gradient stops at |r| <= tolerance·|b| or after
    // maxIterations (then the step goes on with the last iterate and the miss is reported).
    double tolerance = 1e-5;
    int maxIterations = 200;
    Preconditioner preconditioner = Preconditioner::Jacobi;
    // vbd only (docs/integrators.md "vbd"): Gauss–Seidel sweeps over the colours per step, and
    // ρ, the spectral radius estimate of the Chebyshev acceleration; 0 = no acceleration.
    int iterations = 10;
    double chebyshevRho = 0;
    // vbd only: after each of the first translationSweeps sweeps, the Newton step of G on the
    // rigid translation of the free vertices (the mode the sweeps barely move); 0 = none. Once a
    // step by default: docs/integrators.md "vbd", why one.
    int translationSweeps = 1;
    // vbd only: before the first sweep, the same Newton step on the translation of each block of
    // the sheet cut into 2 × 2, then 4 × 4, … 2^L × 2^L equal parts (L = translationLevels; the
    // blocks of a level in four colours): the landing's tension carried across the sheet within
    // the step (docs/integrators.md "vbd", the translation's levels); 0 = none. 4 by default:
    // with them 10 sweeps at 1/60 s hold a landing sheet of 192² where without them it tears
    // from 72², for about a quarter more a step.
    int translationLevels = 4;
    // vbd only, with the levels: more levels than translationLevels where the finest blocks would
    // be wider than this many vertices (vbdTranslationLevels); 0 = exactly translationLevels. 16
    // by default: it adds levels only past 256 vertices a side, where 4 levels' blocks held the
    // landing less far than blocks 16 wide (docs/integrators.md "The translation's levels").
    int translationBlockWidth = 16;
    // vbd only, with the levels: how many times a step they run, before the first sweep and again
    // before sweeps spread evenly over the rest (vbdLevelPassSweep; at most one before each
    // sweep). 1 by default: a second pass holds a landing wherever it meets the collider on sheets
    // where one tears off the blocks' edges, for about 15% more a step (docs/integrators.md).
    int translationLevelPasses = 1;
    // Whether a vbd step takes any translation step (what the CPU keeps the pushes for).
    bool vbdTranslates() const { return translationSweeps > 0 || translationLevels > 0; }
    // Step control (docs/integrators.md "Step control"), any method: a step that stretches a
    // structural spring by more than this fraction of its rest length is redone from its start
    // as two steps of half the Δt, each checked again; 0 = every step is taken as it comes.
    double maxStepStrain = 0;
};

// The integrator keys set away from their defaults that the scene's method does not use
// (implicit_euler's tolerance, max_iterations and preconditioner; vbd's iterations,
// chebyshev_rho, translation_sweeps, translation_levels and translation_level_passes), one line
// each naming the key, its value and whose it is, and vbd's passes of the levels that do not run
// as set (no levels, more passes than sweeps); empty when none.
std::vector<std::string> unusedIntegratorSettings(const IntegratorSpec& integrator);

struct Plane {
    glm::dvec3 point{0}, normal{0, 1, 0};  // normal is unit length
};
struct Sphere {
    glm::dvec3 center{0};
    double radius = 1;  // [m]
};

// {"axis": [x, y, z], "degrees": a} (docs/colliders.md §1): kept as written (the axis
// normalised) so that a saved scene loads back bit for bit; matrix() is local → world.
struct AxisAngle {
    glm::dvec3 axis{0, 0, 1};  // unit length
    double degrees = 0;
    glm::dmat3 matrix() const;
};

// docs/colliders.md §1: an oriented box and a capsule.
struct Box {
    glm::dvec3 center{0};
    glm::dvec3 halfExtents{0.5};  // > 0 [m]
    AxisAngle rotation;
};
struct Capsule {
    glm::dvec3 a{0}, b{0, 1, 0};  // end points of the axis [m]
    double radius = 0.1;          // [m]
};

// A closed OBJ baked once at load into a signed-distance grid (docs/colliders.md §4). The bake
// is shared, so copying a Scene stays cheap.
struct BakedMesh;
struct MeshCollider {
    std::string file;  // the OBJ as the scene names it (relative to the scene's folder)
    std::string path;  // the OBJ's absolute path, which a saved scene writes
    double cell = 0.01, band = 0.05;  // grid spacing and margin [m]
    glm::dvec3 translation{0};
    AxisAngle rotation;  // about the OBJ's origin, before the translation
    std::shared_ptr<const BakedMesh> baked;
};

// A motion in the scene's units (docs/colliders.md §3); motion() gives collider_motion.h's.
struct ColliderMotion {
    MotionType type = MotionType::Linear;
    glm::dvec3 velocity{0};    // linear [m/s]
    glm::dvec3 axis{0, 1, 0};  // rotation, oscillation (unit)
    glm::dvec3 pivot{0};       // rotation [m]
    double degreesPerSecond = 0;
    double amplitude = 0, frequency = 0, phaseDegrees = 0;  // oscillation [m], [Hz], [°]
    Motion motion() const;
};

using ColliderShape = std::variant<Plane, Sphere, Box, Capsule, MeshCollider>;

// One collider: its shape at t = 0, the contact parameters of docs/colliders.md §2, and how it
// moves. A plane or sphere with thickness 0, friction 0 and no motion is DESIGN.md §2's.
struct Collider {
    ColliderShape shape;
    double thickness = 0;  // h [m]
    double friction = 0;   // c_f
    std::optional<ColliderMotion> motion;

    Collider() = default;
    template <typename S>
    requires std::is_constructible_v<ColliderShape, S> Collider(S s)
        : shape(std::move(s)) {}  // NOLINT: a bare shape is a collider
    template <typename S>
    const S* as() const {
        return std::get_if<S>(&shape);
    }
    template <typename S>
    S* as() {
        return std::get_if<S>(&shape);
    }
    bool plain() const { return thickness == 0 && friction == 0 && !motion; }
};

const char* colliderTypeName(const ColliderShape& shape);  // "plane", "sphere", "box", ...

// Contacts of the cloth with itself (docs/physics.md "Self-collision"): non-neighbouring
// elements are kept `thickness` apart; `friction` is the Coulomb coefficient of their sliding.
struct SelfCollision {
    double thickness = 0.004;  // h [m]
    double friction = 0;       // μ
};

struct Wind {
    glm::dvec3 direction{1, 0, 0};  // unit length
    double strength = 0;            // K_w [N]
};

// A pinned vertex: held where it is, or, with `follow` ≥ 0, carried by that collider's motion
// (the collider's pose at t applied to the vertex's grid position; docs/colliders.md §5).
struct Pin {
    int i, j;         // resolved grid indices (negative ones in the file count from the end)
    int follow = -1;  // index in Scene::colliders of a collider with a motion, or -1: still
};

struct Scene {
    std::string name;
    std::string source;  // the file it was loaded from, for messages
    ClothSpec cloth;
    // The per-vertex form (the seed's): one mass per vertex, one stiffness per family, a drag
    // coefficient. Unused when `material` is set.
    SpringStiffness springs;
    double damping = 0;  // μ [N·s/m]
    std::optional<Material> material;
    glm::dvec3 gravity{0, -9.81, 0};
    std::vector<Pin> pins;
    IntegratorSpec integrator;
    std::vector<Collider> colliders;
    std::optional<Wind> wind;
    std::optional<SelfCollision> selfCollision;
    double maxSpeed = 1e4;  // [m/s]; faster is reported as unstable
    // A modelled spring stretched or squeezed by more than this fraction of its rest length is
    // reported as unstable: the run has left the physics a mass-spring cloth stands for.
    double maxStrain = 1;
    double duration = 1;  // simulated time `run` covers without --steps [s]

    Grid grid() const;
    // What the solvers model, from either form. Vertex (i, j)'s mass [kg]: cloth.mass, or its
    // share of the area times the density (corners ¼, edges ½ of a cell's du·dv).
    double vertexMass(int i, int j) const;
    // What the wind's K_w is multiplied by at vertex (i, j): for a material, the vertex's share of
    // the area [m²] (K_w is then a pressure [N/m²], and a finer grid feels the same wind); 1 for
    // the per-vertex form (K_w a force per vertex [N], DESIGN.md §2).
    double windArea(int i, int j) const;
    double totalMass() const;  // [kg]
    // K of the spring of kSpringOffsets[slot] [N/m]; 0: not modelled.
    double slotStiffness(int slot) const;
    // Drag per unit mass c [1/s]: the drag force on vertex k is −c·m_k·v_k (μ/m, or the
    // material's air_damping).
    double dampingRate() const;
    // B of the quadratic bending energy [N·m]; 0 (the per-vertex form): not modelled.
    double bendingStiffness() const;
    // β [s] of the damping along each spring, F = β K ((v_q − v_k)·d̂) d̂ (docs/physics.md
    // "Spring damping"); 0 (and always in the per-vertex form): not modelled.
    double springDamping() const;

    // round(duration / dt), at least 1; InputError (key duration) past 1e12 steps.
    long defaultSteps() const;
    int planeCount() const;
    int sphereCount() const;
    bool anyFriction() const {  // whether a collider has friction (c_f > 0)
        for (const Collider& c : colliders)
            if (c.friction > 0) return true;
        return false;
    }
    template <typename S>
    int count() const {
        int n = 0;
        for (const Collider& c : colliders) n += c.as<S>() != nullptr;
        return n;
    }
};

}  // namespace cloth
