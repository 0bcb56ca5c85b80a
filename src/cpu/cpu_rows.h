// The CPU backend's row kernels: loops over one grid row (or part of one) of structure-of-arrays
// data, vectorised by the compiler across the row. cpu/isa/cpu_rows_isa.cpp is compiled once
// per instruction set (generic x86-64, AVX2+FMA, AVX-512) and the solver picks one at run time:
// the best the CPU has, or the one its options name (the app takes it from CLOTH_CPU_ISA). All of
// them compute the same operations in the same order per vertex (model/spring_math.h), so they
// give the same bits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace cloth {

// `scalar` is not a kernel set: it is the first CPU backend's vertex-by-vertex path, kept as
// the oracle the row kernels are tested against bit for bit.
enum class CpuIsa { Auto, Scalar, Generic, Avx2, Avx512 };

const char* cpuIsaName(CpuIsa isa);
bool cpuIsaSupported(CpuIsa isa);  // by this CPU (Auto and Scalar always)
// "auto", "scalar", "generic", "avx2", "avx512" → the set; nullopt for another name.
std::optional<CpuIsa> cpuIsaFromName(const std::string& name);
// Auto → the widest the CPU supports. Throws InputError (key CLOTH_CPU_ISA, exit 2) for an
// instruction set this CPU lacks.
CpuIsa resolveCpuIsa(CpuIsa requested);

// Three component arrays of a row, already offset to its first element.
template <typename T>
struct Row3 {
    T* x;
    T* y;
    T* z;
    Row3 operator+(std::ptrdiff_t d) const { return {x + d, y + d, z + d}; }
};
template <typename T>
struct ConstRow3 {
    const T* x;
    const T* y;
    const T* z;
    ConstRow3(const T* x_, const T* y_, const T* z_) : x(x_), y(y_), z(z_) {}
    ConstRow3(const Row3<T>& r) : x(r.x), y(r.y), z(r.z) {}  // NOLINT: a row is readable
    ConstRow3 operator+(std::ptrdiff_t d) const { return {x + d, y + d, z + d}; }
};

// One Euler update of a row: the state in (xIn, v), the force f, the new positions into xOut
// (v in place). inverseMass: the row's 1/m_k [1/kg], one per vertex; dampingRate c [1/s]; the
// rest in SI units.
template <typename T>
struct EulerRow {
    ConstRow3<T> xIn, f;
    Row3<T> v, xOut;
    const T* inverseMass;
    T h, dampingRate, gx, gy, gz;
};

// Row j's whole 12-neighbour gather over a run of columns where every neighbour exists: p the
// vertices, q[s] and c[s] the neighbour and the coefficient of spring s of the offset table
// (model/grid.h kSpringOffsets), all at the run's first column. The springs to the rows above
// (kComputedInGather) have their coefficients computed in the same loop, from stiffness[s] and
// restLength[s], and stored through out[s] for the rows above: their square roots and divisions
// then overlap the gather's arithmetic.
template <typename T>
struct GatherRow {
    ConstRow3<T> p{nullptr, nullptr, nullptr};
    ConstRow3<T> q[12]{
        {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr},
        {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr},
        {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr},
        {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr}, {nullptr, nullptr, nullptr}};
    const T* c[12]{};
    T* out[12]{};
    T stiffness[12]{}, restLength[12]{};
};
// A material's bending force (model/bending.h) on a run of interior vertices (two or more from
// every border), all rows at the run's first column: rows[r] is row j − 2 + r, read from two
// columns before the run to two after. wu, wv, t: bendingForce's weights for row j's vertices.
template <typename T>
struct BendingRow {
    ConstRow3<T> rows[5]{{nullptr, nullptr, nullptr},
                         {nullptr, nullptr, nullptr},
                         {nullptr, nullptr, nullptr},
                         {nullptr, nullptr, nullptr},
                         {nullptr, nullptr, nullptr}};
    T wu{}, wv{}, t{};
};

// (0, 1), (1, 1), (−1, 1), (0, 2): the upward springs that are not within the row.
inline constexpr bool kComputedInGather[12] = {false, false, true,  false, true, true,
                                               false, false, false, false, true, false};

// A plane or sphere collider on a row of positions x and velocities v (cpu/cpu_colliders.h),
// with the response of model/collider_contact.h lane by lane: thickness h, friction c_f, and
// when `moving`, the collider's velocity v_c = linear + angular × (p − origin) at each vertex.
// With `touched`, the positions alone (v is left as it is): touched[i] = `mark` where the vertex
// touched (φ < h), as collidePosition says, and unchanged elsewhere.
template <typename T>
struct ContactRow {
    Row3<T> x, v;
    T cx, cy, cz;  // the plane's point or the sphere's centre [m]
    T nx, ny, nz;  // the plane's unit normal
    T radius;      // the sphere's [m]
    T thickness, friction;
    bool moving;
    T lx, ly, lz, ax, ay, az, ox, oy, oz;  // linear [m/s], angular [rad/s], origin [m]
    std::int32_t* touched = nullptr;
    std::int32_t mark = 0;
};

// A plane's or a sphere's row cull (cpu/cpu_colliders.cpp rowMayTouch): whether any of a row's
// positions may touch. Plane: point c, unit normal m, thickness h, magnitude qMag = |c|₁ + |h|
// and the rounding slack; sphere: the bound's centre c and squared radius.
template <typename T>
struct CullRow {
    T cx, cy, cz;
    T mx, my, mz, h, qMag, slack;
    T radius2;
};

// vbd: the Newton steps of a run of one colour's vertices in an interior row (every vertex two
// or more from every border), grid vertex k = first + 5m for m < n, each on its local potential
// as cpu_vbd.cpp's vbdVertex builds it (model/vbd_lane.h: the same operations, the same bits).
// The kernel reads the solver's copy in phases (cpu/cpu_vbd_phases.h), where vertex m of the
// run is at + m and its neighbours lie a fixed offset away; it writes the moved vertices there
// and into the iterate. A pinned vertex, and `skip` (the grabbed one, which the caller steps),
// keep their position; moved[m] says whether vertex m took its step (the caller then applies the
// colliders, with the Hessians the kernel leaves it). With `wholeVectors` the kernel computes
// whole vectors: it reads up to kVbdSlack entries past a run (and past each neighbour's run) in
// every array in phases, and writes moved and the Hessians for n rounded up to a multiple of
// 64 / sizeof(T) (64 entries hold any run of 64 or fewer). The caller sets it only where no other
// thread writes what those reads reach (cpu_vbd.cpp vbdSweep).
inline constexpr std::int64_t kVbdSlack = 64;
template <typename T>
struct VbdRow {
    // The positions in the grid's order: written.
    Row3<T> x{nullptr, nullptr, nullptr};
    // In phases: the iterate, positions x and displacements d = x − x_n (read, written), the
    // inertial target's ŷ = y − x_n, 1/m [1/kg],
    // W_kk (with bending), the pins.
    Row3<T> px{nullptr, nullptr, nullptr}, pd{nullptr, nullptr, nullptr};
    ConstRow3<T> py{nullptr, nullptr, nullptr};
    const T* inverseMass = nullptr;
    const T* bendDiagonal = nullptr;
    const std::uint8_t* pinned = nullptr;
    std::uint8_t* moved = nullptr;
    // first: the run's first vertex in the grid, at: in phases; skip: −1 for none.
    std::int64_t first = 0, at = 0, skip = -1;
    bool wholeVectors = false;
    int springs = 0;            // the stencil's springs, as the solver's springs_
    std::int64_t offset[12]{};  // q − k in phases
    std::int64_t bendAt[13]{};  // bendingLane's 13 stencil vertices, in phases
    T stiffness[12]{}, restLength[12]{}, damping[12]{};
    T h{}, dampingRate{};
    bool bending = false;  // with bending: its weights w_u, w_v, t inside the sheet (bending.h)
    T wu{}, wv{}, t{};
    // With colliders: the contacts in phases (cpu_vbd_phases.h VbdContacts) whose friction
    // enters the local problems (vbdFrictionLane, ε = ε_v h), and where each vertex's local
    // Hessian goes (xx, yy, zz, xy, xz, yz; vertex m of the run at m) for the projection after.
    ConstRow3<T> contactNormal{nullptr, nullptr, nullptr}, contactSlide{nullptr, nullptr, nullptr};
    const T* contactWeight = nullptr;  // null: no colliders
    T epsilon{};
    T* hessian[6]{};
};

// vbd: the Newton steps of up to kSize vertices of one colour anywhere in the grid (the border's,
// whose springs leave the grid or are halved there), gathered by the caller (cpu_vbd_border.cpp)
// lane by lane, so that the kernel computes what vbdVertex computes, in its order, over whole
// vectors: lanes n … n rounded up to 16 hold copies of a gathered vertex. Spring s of lane m is
// absent where present[s][m] is 0 (it leaves the grid): its far end q holds any finite
// position, and the lane keeps the sums without it. The kernel leaves every lane's local problem
// (gradient 3, Hessian 6, as VbdLane) in `lane` and its Newton step in `step` where `stepped`.
template <typename T>
struct VbdBatch {
    static constexpr int kSize = 64;
    alignas(64) T p[3][kSize], d[3][kSize], y[3][kSize];  // x, d = x − x_n, ŷ = y − x_n
    alignas(64) T inverseMass[kSize];
    alignas(64) T q[12][3][kSize], qd[12][3][kSize];  // spring s's far end: position, d
    alignas(64) T stiffness[12][kSize], damping[12][kSize];
    alignas(64) std::uint8_t present[12][kSize];
    alignas(64) T bend[3][kSize], bendDiagonal[kSize];  // bendingForce, W_kk (with bending)
    alignas(64) T slide[3][kSize], normal[3][kSize], weight[kSize];  // the contact (friction)
    alignas(64) T lane[9][kSize], step[3][kSize];
    alignas(64) std::uint8_t stepped[kSize];
    int springs = 0;
    T restLength[12]{};
    bool damped[12]{};
    T h{}, dampingRate{}, epsilon{};
    bool bending = false, friction = false;
};

// Every kernel runs over n elements from the given (already offset) pointers.
template <typename T>
struct RowKernels {
    // c_i = springCoefficient(q_i − p_i, K, L): one spring per element, shared by its two ends.
    void (*coefficients)(ConstRow3<T> p, ConstRow3<T> q, T stiffness, T restLength, T* c, int n);
    // f_i += c_i (q_i − p_i): one spring of the 12-neighbour gather.
    void (*accumulate)(Row3<T> f, ConstRow3<T> p, ConstRow3<T> q, const T* c, int n);
    // f_i = Σ_s c_s,i (q_s,i − p_i) over the modelled families in table order, f in registers:
    // the same sums as accumulate spring by spring. Indexed by the families modelled, bit 0
    // structural, 1 shear, 2 bend.
    void (*gather[8])(Row3<T> f, const GatherRow<T>& row, int n);
    // f_i += wind on the normal from a = right_i − left_i, b = up_i − down_i.
    void (*wind)(Row3<T> f, ConstRow3<T> left, ConstRow3<T> right, ConstRow3<T> down,
                 ConstRow3<T> up, T wx, T wy, T wz, T strength, int n);
    void (*explicitEuler)(const EulerRow<T>& row, int n);
    void (*symplecticEuler)(const EulerRow<T>& row, int n);
    // Whether any element is unstable (spring_math.h badVertex).
    bool (*anyBad)(ConstRow3<T> x, ConstRow3<T> v, T maxSpeed2, int n);
    // collide() of model/collider_contact.h for a plane or a sphere, branch-free: the same bits.
    void (*planeContact)(const ContactRow<T>& row, int n);
    void (*sphereContact)(const ContactRow<T>& row, int n);
    // f_i += bendingForce at each interior vertex of the run, in its order of operations: the
    // scalar path's bits.
    void (*bending)(Row3<T> f, const BendingRow<T>& row, int n);
    // c_i = springDampingCoefficient (model/spring_math.h) of one spring per element, from p_i
    // to q_i with velocities vp_i, vq_i, dampingK = βK [N·s/m]: shared by its two ends, which
    // add c_i (q_i − p_i) with accumulate.
    void (*dampingCoefficients)(ConstRow3<T> p, ConstRow3<T> q, ConstRow3<T> vp, ConstRow3<T> vq,
                                T dampingK, T restLength, T* c, int n);
    void (*vbd)(const VbdRow<T>& row, int n);
    void (*vbdBatch)(VbdBatch<T>& batch, int n);
    // The row culls of CullRow, in its operations (the same answers at any width).
    bool (*planeMayTouch)(ConstRow3<T> x, const CullRow<T>& cull, int n);
    bool (*sphereMayTouch)(ConstRow3<T> x, const CullRow<T>& cull, int n);
};

template <typename T>
const RowKernels<T>& rowKernels(CpuIsa isa);  // Generic, Avx2 or Avx512

// What each instruction set's translation unit defines.
#define CLOTH_DECLARE_ROW_KERNELS(ns)                       \
    namespace ns {                                          \
    template <typename T>                                   \
    const RowKernels<T>& rowKernels();                      \
    extern template const RowKernels<float>& rowKernels();  \
    extern template const RowKernels<double>& rowKernels(); \
    }
CLOTH_DECLARE_ROW_KERNELS(isa_generic)
CLOTH_DECLARE_ROW_KERNELS(isa_avx2)
CLOTH_DECLARE_ROW_KERNELS(isa_avx512)
#undef CLOTH_DECLARE_ROW_KERNELS

}  // namespace cloth
