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
#include "model/bending.h"
#include "model/contact_math.h"
#include "model/spring_math.h"

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

// cpu_colliders.cpp rowMayTouch's culls, in its operations.
template <typename T>
bool planeMayTouch(ConstRow3<T> x, const CullRow<T>& c, int n) {
    const T* __restrict px = x.x, * __restrict py = x.y, * __restrict pz = x.z;
    const T qx = c.cx, qy = c.cy, qz = c.cz, mx = c.mx, my = c.my, mz = c.mz;
    const T h = c.h, qMag = c.qMag, slack = c.slack;
    int hits = 0;
    for (int i = 0; i < n; ++i) {
        const T s = (px[i] - qx) * mx + (py[i] - qy) * my + (pz[i] - qz) * mz;
        const T mag = std::abs(px[i]) + std::abs(py[i]) + std::abs(pz[i]) + qMag;
        hits |= int(s < h + slack * mag);
    }
    return hits != 0;
}

template <typename T>
bool sphereMayTouch(ConstRow3<T> x, const CullRow<T>& c, int n) {
    const T* __restrict px = x.x, * __restrict py = x.y, * __restrict pz = x.z;
    const T bx = c.cx, by = c.cy, bz = c.cz, r2 = c.radius2;
    int hits = 0;
    for (int i = 0; i < n; ++i) {
        const T dx = px[i] - bx, dy = py[i] - by, dz = pz[i] - bz;
        hits |= int(dx * dx + dy * dy + dz * dz < r2);
    }
    return hits != 0;
}

// The shape's φ and normal at (x, y, z), in the same operations and order as collider_shapes.h
// (glm's dot is (x + y) + z, ...), whether the vertex touches (φ < h) and where the push puts it:
// the plane's p + (h − φ) n, the sphere's c + (R + h) n (collider_contact.h pushOut).
template <typename T>
struct ContactShape {
    T cx, cy, cz, mx, my, mz, radius, h;
};
template <typename T, bool kSphere>
CLOTH_LANE bool contactPush(const ContactShape<T>& c, T x, T y, T z, T& nx, T& ny, T& nz, T& qx,
                            T& qy, T& qz) {
    T phi;
    if constexpr (kSphere) {
        const T rx = x - c.cx, ry = y - c.cy, rz = z - c.cz;
        const T len = std::sqrt((rx * rx + ry * ry) + rz * rz);
        phi = len - c.radius;
        const bool away = len > T(0);
        nx = away ? rx / len : T(0);
        ny = away ? ry / len : T(1);
        nz = away ? rz / len : T(0);
        const T shell = c.radius + c.h;
        qx = c.cx + shell * nx;
        qy = c.cy + shell * ny;
        qz = c.cz + shell * nz;
    } else {
        nx = c.mx;
        ny = c.my;
        nz = c.mz;
        phi = ((x - c.cx) * nx + (y - c.cy) * ny) + (z - c.cz) * nz;
        const T push = c.h - phi;
        qx = x + push * nx;
        qy = y + push * ny;
        qz = z + push * nz;
    }
    return phi < c.h;
}

// model/collider_contact.h's collide() for a plane (kSphere false) or a sphere, every lane
// computed and the result selected: contactPush, then the response's own lane function: the same
// bits.
template <typename T, bool kSphere, bool kFriction, bool kMoving>
void contactLoop(T* __restrict px, T* __restrict py, T* __restrict pz, T* __restrict vx,
                 T* __restrict vy, T* __restrict vz, const ContactRow<T>& r, int n) {
    // Every parameter in a local: loads through r inside the loop would stop the vectoriser.
    const ContactShape<T> shape{r.cx, r.cy, r.cz, r.nx, r.ny, r.nz, r.radius, r.thickness};
    const T cf = r.friction;
    const T lx = r.lx, ly = r.ly, lz = r.lz, ax = r.ax, ay = r.ay, az = r.az;
    const T ox0 = r.ox, oy0 = r.oy, oz0 = r.oz;
    // The six arrays are distinct (restrict); say so to GCC, which otherwise versions the loop
    // for aliasing and gives up past ten checks.
    CLOTH_IVDEP
    for (int i = 0; i < n; ++i) {
        const T x = px[i], y = py[i], z = pz[i];
        T nx, ny, nz, qx, qy, qz;
        const bool touch = contactPush<T, kSphere>(shape, x, y, z, nx, ny, nz, qx, qy, qz);
        T ux = T(0), uy = T(0), uz = T(0);  // v_c at the vertex, before its projection
        if constexpr (kMoving) {
            const T dx = x - ox0, dy = y - oy0, dz = z - oz0;
            ux = lx + (ay * dz - dy * az);
            uy = ly + (az * dx - dz * ax);
            uz = lz + (ax * dy - dx * ay);
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
// collidePosition() alone (ContactRow::touched): the positions as contactLoop moves them, and
// which vertices touched.
template <typename T, bool kSphere>
void contactPositionsLoop(T* __restrict px, T* __restrict py, T* __restrict pz,
                          std::int32_t* __restrict touched, const ContactRow<T>& r, int n) {
    const ContactShape<T> shape{r.cx, r.cy, r.cz, r.nx, r.ny, r.nz, r.radius, r.thickness};
    const std::int32_t mark = r.mark;
    CLOTH_IVDEP
    for (int i = 0; i < n; ++i) {
        const T x = px[i], y = py[i], z = pz[i];
        T nx, ny, nz, qx, qy, qz;
        const bool touch = contactPush<T, kSphere>(shape, x, y, z, nx, ny, nz, qx, qy, qz);
        px[i] = touch ? qx : x;
        py[i] = touch ? qy : y;
        pz[i] = touch ? qz : z;
        touched[i] = touch ? mark : touched[i];
    }
}
template <typename T, bool kSphere>
void contact(const ContactRow<T>& r, int n) {
    if (r.touched) return contactPositionsLoop<T, kSphere>(r.x.x, r.x.y, r.x.z, r.touched, r, n);
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

}  // namespace

// cpu_vbd_isa.cpp, compiled with this file for the same instruction set.
template <typename T>
void vbd(const VbdRow<T>& r, int n);
extern template void vbd(const VbdRow<float>&, int);
extern template void vbd(const VbdRow<double>&, int);
template <typename T>
void vbdBatch(VbdBatch<T>& b, int n);
extern template void vbdBatch(VbdBatch<float>&, int);
extern template void vbdBatch(VbdBatch<double>&, int);

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
                                       &vbd<T>,
                                       &vbdBatch<T>,
                                       &planeMayTouch<T>,
                                       &sphereMayTouch<T>};
    return kernels;
}
template const RowKernels<float>& rowKernels();
template const RowKernels<double>& rowKernels();

}  // namespace cloth::CLOTH_ISA_NS
