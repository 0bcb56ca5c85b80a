// The row kernels of cpu/cpu_rows.h for one instruction set: CMake compiles this file once per
// set with CLOTH_ISA_NS naming the namespace and that set's -m flags, plus -ffp-contract=off (no
// FMA: the same bits as the scalar path), -fno-math-errno (sqrt vectorises) and
// -fno-trapping-math (a conditional division vectorises without AVX-512 masks). Plain loops over
// restrict-qualified arrays: the compiler vectorises each across the row. No standard-library
// templates here, so no out-of-line copy compiled for a wider ISA can leak into generic code.
#include <cmath>
#include <cstdint>
#include <type_traits>

#include "cpu/cpu_rows.h"
#include "model/contact_math.h"
#include "model/spring_math.h"
#include "model/vbd_lane.h"

#ifndef CLOTH_ISA_NS
#error "CLOTH_ISA_NS names the instruction set this file is compiled for"
#endif

// The loop's arrays do not overlap (each is a restrict parameter or a distinct row): GCC may
// vectorise without run-time alias checks. Clang (the fuzzer's build) has no such pragma.
#if defined(__GNUC__) && !defined(__clang__)
#define CLOTH_IVDEP _Pragma("GCC ivdep")
#else
#define CLOTH_IVDEP
#endif

namespace cloth::CLOTH_ISA_NS {
namespace {

// Every array a parameter of its own, restrict-qualified: GCC then knows the stores do not
// alias the loads and vectorises (positions may alias each other: they are only read).
template <typename T>
void coefficientLoop(const T* __restrict px, const T* __restrict py, const T* __restrict pz,
                     const T* __restrict qx, const T* __restrict qy, const T* __restrict qz,
                     T stiffness, T restLength, T* __restrict c, int n) {
    for (int i = 0; i < n; ++i)
        c[i] =
            springCoefficient(qx[i] - px[i], qy[i] - py[i], qz[i] - pz[i], stiffness, restLength);
}
template <typename T>
void coefficients(ConstRow3<T> p, ConstRow3<T> q, T stiffness, T restLength, T* c, int n) {
    coefficientLoop(p.x, p.y, p.z, q.x, q.y, q.z, stiffness, restLength, c, n);
}

template <typename T>
void accumulateLoop(T* __restrict fx, T* __restrict fy, T* __restrict fz, const T* __restrict px,
                    const T* __restrict py, const T* __restrict pz, const T* __restrict qx,
                    const T* __restrict qy, const T* __restrict qz, const T* __restrict c, int n) {
    for (int i = 0; i < n; ++i) {
        fx[i] += c[i] * (qx[i] - px[i]);
        fy[i] += c[i] * (qy[i] - py[i]);
        fz[i] += c[i] * (qz[i] - pz[i]);
    }
}
template <typename T>
void accumulate(Row3<T> f, ConstRow3<T> p, ConstRow3<T> q, const T* c, int n) {
    accumulateLoop(f.x, f.y, f.z, p.x, p.y, p.z, q.x, q.y, q.z, c, n);
}

// Spring damping coefficients (spring_math.h springDampingCoefficient): one spring per element,
// its far end q.
template <typename T>
void dampingLoop(const T* __restrict px, const T* __restrict py, const T* __restrict pz,
                 const T* __restrict qx, const T* __restrict qy, const T* __restrict qz,
                 const T* __restrict ux, const T* __restrict uy, const T* __restrict uz,
                 const T* __restrict wx, const T* __restrict wy, const T* __restrict wz, T dampingK,
                 T restLength, T* __restrict c, int n) {
    for (int i = 0; i < n; ++i)
        c[i] = springDampingCoefficient(qx[i] - px[i], qy[i] - py[i], qz[i] - pz[i], wx[i] - ux[i],
                                        wy[i] - uy[i], wz[i] - uz[i], dampingK, restLength);
}
template <typename T>
void dampingCoefficients(ConstRow3<T> p, ConstRow3<T> q, ConstRow3<T> vp, ConstRow3<T> vq,
                         T dampingK, T restLength, T* c, int n) {
    dampingLoop(p.x, p.y, p.z, q.x, q.y, q.z, vp.x, vp.y, vp.z, vq.x, vq.y, vq.z, dampingK,
                restLength, c, n);
}

template <typename T, int kFamilies>
void gather(Row3<T> f, const GatherRow<T>& g, int n) {
    T* __restrict fx = f.x;
    T* __restrict fy = f.y;
    T* __restrict fz = f.z;
    CLOTH_IVDEP
    for (int i = 0; i < n; ++i) {
        const T px = g.p.x[i], py = g.p.y[i], pz = g.p.z[i];
        T x = T(0), y = T(0), z = T(0);
#pragma GCC unroll 12
        for (int s = 0; s < 12; ++s) {
            if (!((kFamilies >> (s / 4)) & 1)) continue;  // springs 4f … 4f+3 are family f
            T c;
            if (kComputedInGather[s]) {
                c = springCoefficient(g.q[s].x[i] - px, g.q[s].y[i] - py, g.q[s].z[i] - pz,
                                      g.stiffness[s], g.restLength[s]);
                g.out[s][i] = c;
            } else {
                c = g.c[s][i];
            }
            x += c * (g.q[s].x[i] - px);
            y += c * (g.q[s].y[i] - py);
            z += c * (g.q[s].z[i] - pz);
        }
        fx[i] = x;
        fy[i] = y;
        fz[i] = z;
    }
}

template <typename T>
void windLoop(T* __restrict fx, T* __restrict fy, T* __restrict fz, const T* __restrict lx,
              const T* __restrict ly, const T* __restrict lz, const T* __restrict rx,
              const T* __restrict ry, const T* __restrict rz, const T* __restrict dx,
              const T* __restrict dy, const T* __restrict dz, const T* __restrict ux,
              const T* __restrict uy, const T* __restrict uz, T wx, T wy, T wz, T strength, int n) {
    for (int i = 0; i < n; ++i) {
        T nx, ny, nz;
        unitNormal(rx[i] - lx[i], ry[i] - ly[i], rz[i] - lz[i], ux[i] - dx[i], uy[i] - dy[i],
                   uz[i] - dz[i], nx, ny, nz);
        addWind(nx, ny, nz, wx, wy, wz, strength, fx[i], fy[i], fz[i]);
    }
}
template <typename T>
void wind(Row3<T> f, ConstRow3<T> left, ConstRow3<T> right, ConstRow3<T> down, ConstRow3<T> up,
          T wx, T wy, T wz, T strength, int n) {
    windLoop(f.x, f.y, f.z, left.x, left.y, left.z, right.x, right.y, right.z, down.x, down.y,
             down.z, up.x, up.y, up.z, wx, wy, wz, strength, n);
}

template <typename T, bool kSymplectic>
void eulerLoop(const T* __restrict xx, const T* __restrict xy, const T* __restrict xz,
               const T* __restrict fx, const T* __restrict fy, const T* __restrict fz,
               T* __restrict vx, T* __restrict vy, T* __restrict vz, T* __restrict px,
               T* __restrict py, T* __restrict pz, const T* __restrict inverseMass, T h, T c, T gx,
               T gy, T gz, int n) {
    for (int i = 0; i < n; ++i) {
        T x = xx[i], y = xy[i], z = xz[i];
        T u = vx[i], v = vy[i], s = vz[i];
        const T w = inverseMass[i];
        eulerComponent<T, kSymplectic>(x, u, fx[i], h, c, w, gx);
        eulerComponent<T, kSymplectic>(y, v, fy[i], h, c, w, gy);
        eulerComponent<T, kSymplectic>(z, s, fz[i], h, c, w, gz);
        px[i] = x;
        py[i] = y;
        pz[i] = z;
        vx[i] = u;
        vy[i] = v;
        vz[i] = s;
    }
}
template <typename T, bool kSymplectic>
void euler(const EulerRow<T>& r, int n) {
    eulerLoop<T, kSymplectic>(r.xIn.x, r.xIn.y, r.xIn.z, r.f.x, r.f.y, r.f.z, r.v.x, r.v.y, r.v.z,
                              r.xOut.x, r.xOut.y, r.xOut.z, r.inverseMass, r.h, r.dampingRate, r.gx,
                              r.gy, r.gz, n);
}

template <typename T>
bool anyBad(ConstRow3<T> x, ConstRow3<T> v, T maxSpeed2, int n) {
    const T* __restrict px = x.x, * __restrict py = x.y, * __restrict pz = x.z;
    const T* __restrict vx = v.x, * __restrict vy = v.y, * __restrict vz = v.z;
    int bad = 0;
    for (int i = 0; i < n; ++i)
        bad |= int(badVertex(px[i], py[i], pz[i], vx[i], vy[i], vz[i], maxSpeed2));
    return bad != 0;
}

// model/collider_contact.h's collide() for a plane (kSphere false) or a sphere, every lane
// computed and the result selected: the shape's φ and normal in the same operations and order as
// collider_shapes.h (glm's dot is (x + y) + z, its cross a.y·b.z − b.y·a.z, ...), then the
// response's own lane function: the same bits.
template <typename T, bool kSphere, bool kFriction, bool kMoving>
void contactLoop(T* __restrict px, T* __restrict py, T* __restrict pz, T* __restrict vx,
                 T* __restrict vy, T* __restrict vz, const ContactRow<T>& r, int n) {
    // Every parameter in a local: loads through r inside the loop would stop the vectoriser.
    const T cx = r.cx, cy = r.cy, cz = r.cz, h = r.thickness, cf = r.friction, radius = r.radius;
    const T mx = r.nx, my = r.ny, mz = r.nz;
    const T lx = r.lx, ly = r.ly, lz = r.lz, ax = r.ax, ay = r.ay, az = r.az;
    const T ox0 = r.ox, oy0 = r.oy, oz0 = r.oz;
    const T shell = radius + h;
    // The six arrays are distinct (restrict); say so to GCC, which otherwise versions the loop
    // for aliasing and gives up past ten checks.
    CLOTH_IVDEP
    for (int i = 0; i < n; ++i) {
        const T x = px[i], y = py[i], z = pz[i];
        T phi, nx, ny, nz;
        if constexpr (kSphere) {
            const T rx = x - cx, ry = y - cy, rz = z - cz;
            const T len = std::sqrt((rx * rx + ry * ry) + rz * rz);
            phi = len - radius;
            const bool away = len > T(0);
            nx = away ? rx / len : T(0);
            ny = away ? ry / len : T(1);
            nz = away ? rz / len : T(0);
        } else {
            nx = mx;
            ny = my;
            nz = mz;
            phi = ((x - cx) * nx + (y - cy) * ny) + (z - cz) * nz;
        }
        T ux = T(0), uy = T(0), uz = T(0);  // v_c at the vertex, before its projection
        if constexpr (kMoving) {
            const T dx = x - ox0, dy = y - oy0, dz = z - oz0;
            ux = lx + (ay * dz - dy * az);
            uy = ly + (az * dx - dz * ax);
            uz = lz + (ax * dy - dx * ay);
        }
        const bool touch = phi < h;
        T qx, qy, qz;
        if constexpr (kSphere) {
            qx = cx + shell * nx;
            qy = cy + shell * ny;
            qz = cz + shell * nz;
        } else {
            const T push = h - phi;
            qx = x + push * nx;
            qy = y + push * ny;
            qz = z + push * nz;
        }
        const T v0x = vx[i], v0y = vy[i], v0z = vz[i];
        T ox = v0x, oy = v0y, oz = v0z;
        respondVelocityLane<T, kFriction>(ox, oy, oz, nx, ny, nz, ux, uy, uz, cf);
        px[i] = touch ? qx : x;
        py[i] = touch ? qy : y;
        pz[i] = touch ? qz : z;
        vx[i] = touch ? ox : v0x;
        vy[i] = touch ? oy : v0y;
        vz[i] = touch ? oz : v0z;
    }
}
template <typename T, bool kSphere>
void contact(const ContactRow<T>& r, int n) {
    const bool friction = r.friction > T(0);
    auto run = [&](auto kFriction, auto kMoving) {
        contactLoop<T, kSphere, decltype(kFriction)::value, decltype(kMoving)::value>(
            r.x.x, r.x.y, r.x.z, r.v.x, r.v.y, r.v.z, r, n);
    };
    using Yes = std::true_type;
    using No = std::false_type;
    if (friction && r.moving) return run(Yes{}, Yes{});
    if (friction) return run(Yes{}, No{});
    if (r.moving) return run(No{}, Yes{});
    run(No{}, No{});
}

// model/bending.h bendingForce at an interior vertex, one component: the same operations in the
// same order (the second differences along u and v centred at i − 1, i, i + 1 and at j − 1, j,
// j + 1 with coefficients 1, −2, 1, then the twists of the cells (i − 1, j − 1), (i − 1, j),
// (i, j − 1), (i, j) with signs +, −, −, +), added to f at the end as forceRow does.
template <typename T>
CLOTH_LANE T bendingAt(const T* r0, const T* r1, const T* r2, const T* r3, const T* r4,
                       std::int64_t i, T u1, T u0, T v1, T v0, T plus, T minus) {
    return bendingLane(r2[i - 2], r2[i - 1], r2[i], r2[i + 1], r2[i + 2], r1[i - 1], r1[i],
                       r1[i + 1], r3[i - 1], r3[i], r3[i + 1], r0[i], r4[i], u1, u0, v1, v0, plus,
                       minus);
}
template <typename T>
void bendingLoop(T* __restrict f, const T* __restrict r0, const T* __restrict r1,
                 const T* __restrict r2, const T* __restrict r3, const T* __restrict r4, T wu, T wv,
                 T t, int n) {
    const T u1 = wu * T(1), u0 = wu * T(-2), v1 = wv * T(1), v0 = wv * T(-2);
    const T plus = t * T(1), minus = t * T(-1);
    for (int i = 0; i < n; ++i)
        f[i] += bendingAt(r0, r1, r2, r3, r4, i, u1, u0, v1, v0, plus, minus);
}
template <typename T>
void bending(Row3<T> f, const BendingRow<T>& g, int n) {
    const ConstRow3<T>* r = g.rows;
    bendingLoop(f.x, r[0].x, r[1].x, r[2].x, r[3].x, r[4].x, g.wu, g.wv, g.t, n);
    bendingLoop(f.y, r[0].y, r[1].y, r[2].y, r[3].y, r[4].y, g.wu, g.wv, g.t, n);
    bendingLoop(f.z, r[0].z, r[1].z, r[2].z, r[3].z, r[4].z, g.wu, g.wv, g.t, n);
}

// vbd (cpu_rows.h VbdRow) on up to kVbdChunk vertices from k0: each term of the local problems
// in a loop of its own over the chunk's vertices, their sums kept in the chunk's arrays, so each
// loop vectorises across the vertices (their loads five apart); then the Newton steps, and the
// stores after every step is taken.
constexpr int kVbdChunk = 64;

template <typename T>
struct VbdChunk {
    alignas(64) T gx[kVbdChunk], gy[kVbdChunk], gz[kVbdChunk];
    alignas(64) T xx[kVbdChunk], yy[kVbdChunk], zz[kVbdChunk];
    alignas(64) T xy[kVbdChunk], xz[kVbdChunk], yz[kVbdChunk];
    alignas(64) T nx[kVbdChunk], ny[kVbdChunk], nz[kVbdChunk];
    CLOTH_LANE VbdLane<T> get(int m) const {
        return {gx[m], gy[m], gz[m], xx[m], yy[m], zz[m], xy[m], xz[m], yz[m]};
    }
    CLOTH_LANE void set(int m, const VbdLane<T>& a) {
        gx[m] = a.gx, gy[m] = a.gy, gz[m] = a.gz, xx[m] = a.xx, yy[m] = a.yy, zz[m] = a.zz;
        xy[m] = a.xy, xz[m] = a.xz, yz[m] = a.yz;
    }
};

// The chunk's new positions into the iterate, where the vertex moved (in its own function: the
// steps above read the iterate through restrict pointers).
template <typename T>
void vbdStore(T* __restrict x, T* __restrict y, T* __restrict z, const VbdChunk<T>& c,
              const std::uint8_t* __restrict moved, std::int64_t k0, int n) {
    for (int m = 0; m < n; ++m) {
        if (!moved[m]) continue;
        const std::int64_t k = k0 + 5 * std::int64_t(m);
        x[k] = c.nx[m], y[k] = c.ny[m], z[k] = c.nz[m];
    }
}

// One component of the inertia's gradient, g_m = inertia·(x − y) + drag·(x − x_n) for the
// chunk's vertices m (x, x_n five apart, y fifteen: its three components interleaved).
template <typename T>
void vbdInertiaLoop(T* __restrict g, const T* __restrict x, const T* __restrict y,
                    const T* __restrict start, const T* __restrict inverseMass, T h, T dampingRate,
                    int n) {
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = 5 * std::int64_t(m);
        const T mass = T(1) / inverseMass[k];
        g[m] = T(0) + vbdInertiaGradient(x[k], y[3 * k], start[k], vbdInertiaWeight(mass, h),
                                         vbdDragWeight(mass, h, dampingRate));
    }
}

// One component of the bending force subtracted from g, the 13 stencil values through pointers
// of their own (each at the chunk's first vertex, five apart): with offsets the compiler could
// see, it would group the loads and give up on the group of five (hence not inlined either).
template <typename T>
[[gnu::noinline]] void vbdBendingLoop(T* __restrict g, const T* const (&p)[13], T u1, T u0, T v1, T v0, T plus,
                    T minus, int n) {
    const T* __restrict a0 = p[0], * __restrict a1 = p[1], * __restrict a2 = p[2];
    const T* __restrict a3 = p[3], * __restrict a4 = p[4], * __restrict b0 = p[5];
    const T* __restrict b1 = p[6], * __restrict b2 = p[7], * __restrict c0 = p[8];
    const T* __restrict c1 = p[9], * __restrict c2 = p[10], * __restrict d = p[11];
    const T* __restrict e = p[12];
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = 5 * std::int64_t(m);
        g[m] -= bendingLane(a0[k], a1[k], a2[k], a3[k], a4[k], b0[k], b1[k], b2[k], c0[k], c1[k],
                            c2[k], d[k], e[k], u1, u0, v1, v0, plus, minus);
    }
}

template <typename T>
void vbdChunk(const VbdRow<T>& r, std::int64_t k0, int n, std::uint8_t* __restrict moved) {
    VbdChunk<T> c;
    const T* __restrict px = r.x.x, * __restrict py = r.x.y, * __restrict pz = r.x.z;
    const T* __restrict nx = r.xn.x, * __restrict ny = r.xn.y, * __restrict nz = r.xn.z;
    const T* __restrict inverseMass = r.inverseMass;
    const T h = r.h, dampingRate = r.dampingRate;
    const std::int64_t skip = r.skip;
    // The inertia first, as addVbdInertia starts the sum from zero.
    vbdInertiaLoop(c.gx, px + k0, r.inertial + 3 * k0, nx + k0, inverseMass + k0, h, dampingRate,
                   n);
    vbdInertiaLoop(c.gy, py + k0, r.inertial + 3 * k0 + 1, ny + k0, inverseMass + k0, h,
                   dampingRate, n);
    vbdInertiaLoop(c.gz, pz + k0, r.inertial + 3 * k0 + 2, nz + k0, inverseMass + k0, h,
                   dampingRate, n);
    for (int m = 0; m < n; ++m) {
        const T mass = T(1) / inverseMass[k0 + 5 * std::int64_t(m)];
        const T diagonal = T(0) + (vbdInertiaWeight(mass, h) + vbdDragWeight(mass, h, dampingRate));
        c.xx[m] = diagonal, c.yy[m] = diagonal, c.zz[m] = diagonal;
        c.xy[m] = T(0), c.xz[m] = T(0), c.yz[m] = T(0);
    }
    for (int s = 0; s < r.springs; ++s) {
        const std::int64_t o = r.offset[s];
        const T K = r.stiffness[s], L = r.restLength[s], beta = r.damping[s];
        if (beta > 0) {
            for (int m = 0; m < n; ++m) {
                const std::int64_t k = k0 + 5 * std::int64_t(m), q = k + o;
                VbdLane<T> a = c.get(m);
                vbdSpringLane(px[q] - px[k], py[q] - py[k], pz[q] - pz[k], K, L, a);
                vbdSpringDampingLane(nx[q] - nx[k], ny[q] - ny[k], nz[q] - nz[k],
                                     (px[q] - nx[q]) - (px[k] - nx[k]),
                                     (py[q] - ny[q]) - (py[k] - ny[k]),
                                     (pz[q] - nz[q]) - (pz[k] - nz[k]), beta, L, h, a);
                c.set(m, a);
            }
        } else {
            for (int m = 0; m < n; ++m) {
                const std::int64_t k = k0 + 5 * std::int64_t(m), q = k + o;
                VbdLane<T> a = c.get(m);
                vbdSpringLane(px[q] - px[k], py[q] - py[k], pz[q] - pz[k], K, L, a);
                c.set(m, a);
            }
        }
    }
    if (r.bending) {
        const T u1 = r.wu * T(1), u0 = r.wu * T(-2), v1 = r.wv * T(1), v0 = r.wv * T(-2);
        const T plus = r.t * T(1), minus = r.t * T(-1);
        const std::int64_t nu = r.nu;
        // bendingLane's order: row j's columns −2 … 2, row j − 1's and j + 1's −1 … 1, rows j ∓ 2.
        const std::int64_t at[13] = {-2,      -1,     0,  1,      2,       -nu - 1, -nu,
                                     -nu + 1, nu - 1, nu, nu + 1, -2 * nu, 2 * nu};
        for (int axis = 0; axis < 3; ++axis) {
            const T* base = (axis == 0 ? px : axis == 1 ? py : pz) + k0;
            const T* p[13];
            for (int e = 0; e < 13; ++e) p[e] = base + at[e];
            vbdBendingLoop(axis == 0   ? c.gx
                           : axis == 1 ? c.gy
                                       : c.gz,
                           p, u1, u0, v1, v0, plus, minus, n);
        }
        const T* __restrict w = r.bendDiagonal;
        for (int m = 0; m < n; ++m) {
            const T s = w[k0 + 5 * std::int64_t(m)];
            c.xx[m] += s, c.yy[m] += s, c.zz[m] += s;
        }
    }
    const std::uint8_t* __restrict pinned = r.pinned;
    for (int m = 0; m < n; ++m) {
        const std::int64_t k = k0 + 5 * std::int64_t(m);
        const T mass = T(1) / inverseMass[k];
        T x = px[k], yk = py[k], z = pz[k];
        const bool stepped = vbdNewtonLane(c.get(m), double(mass) / (double(h) * h), x, yk, z);
        c.nx[m] = x, c.ny[m] = yk, c.nz[m] = z;
        const bool free = pinned[k] == 0;  // read in every lane: no masked load
        moved[m] = std::uint8_t(unsigned(stepped) & unsigned(free) & unsigned(k != skip));
    }
    vbdStore(r.x.x, r.x.y, r.x.z, c, moved, k0, n);
}

template <typename T>
void vbd(const VbdRow<T>& r, int n) {
    for (int m = 0; m < n; m += kVbdChunk)
        vbdChunk(r, r.first + 5 * std::int64_t(m), n - m < kVbdChunk ? n - m : kVbdChunk,
                 r.moved + m);
}

}  // namespace

template <typename T>
const RowKernels<T>& rowKernels() {
    static const RowKernels<T> kernels{&coefficients<T>,
                                       &accumulate<T>,
                                       {&gather<T, 0>, &gather<T, 1>, &gather<T, 2>, &gather<T, 3>,
                                        &gather<T, 4>, &gather<T, 5>, &gather<T, 6>, &gather<T, 7>},
                                       &wind<T>,
                                       &euler<T, false>,
                                       &euler<T, true>,
                                       &anyBad<T>,
                                       &contact<T, false>,
                                       &contact<T, true>,
                                       &bending<T>,
                                       &dampingCoefficients<T>,
                                       &vbd<T>};
    return kernels;
}
template const RowKernels<float>& rowKernels();
template const RowKernels<double>& rowKernels();

}  // namespace cloth::CLOTH_ISA_NS
