// The row kernels of core/cpu_rows.h for one instruction set: CMake compiles this file once per
// set with CLOTH_ISA_NS naming the namespace and that set's -m flags, plus -ffp-contract=off (no
// FMA: the same bits as the scalar path) and -fno-math-errno (sqrt vectorises). Plain loops over
// restrict-qualified arrays: the compiler vectorises each across the row. No standard-library
// templates here, so no out-of-line copy compiled for a wider ISA can leak into generic code.
#include "core/cpu_rows.h"
#include "core/spring_math.h"

#ifndef CLOTH_ISA_NS
#error "CLOTH_ISA_NS names the instruction set this file is compiled for"
#endif

namespace cloth::CLOTH_ISA_NS {
namespace {

template <typename T>
void coefficients(ConstRow3<T> p, ConstRow3<T> q, T stiffness, T restLength, T* __restrict c,
                  int n) {
    for (int i = 0; i < n; ++i)
        c[i] = springCoefficient(q.x[i] - p.x[i], q.y[i] - p.y[i], q.z[i] - p.z[i], stiffness,
                                 restLength);
}

template <typename T>
void accumulate(Row3<T> f, ConstRow3<T> p, ConstRow3<T> q, const T* c, int n) {
    T* __restrict fx = f.x;
    T* __restrict fy = f.y;
    T* __restrict fz = f.z;
    for (int i = 0; i < n; ++i) {
        fx[i] += c[i] * (q.x[i] - p.x[i]);
        fy[i] += c[i] * (q.y[i] - p.y[i]);
        fz[i] += c[i] * (q.z[i] - p.z[i]);
    }
}

template <typename T>
void wind(Row3<T> f, ConstRow3<T> left, ConstRow3<T> right, ConstRow3<T> down, ConstRow3<T> up,
          T wx, T wy, T wz, T strength, int n) {
    T* __restrict fx = f.x;
    T* __restrict fy = f.y;
    T* __restrict fz = f.z;
    for (int i = 0; i < n; ++i) {
        T nx, ny, nz;
        unitNormal(right.x[i] - left.x[i], right.y[i] - left.y[i], right.z[i] - left.z[i],
                   up.x[i] - down.x[i], up.y[i] - down.y[i], up.z[i] - down.z[i], nx, ny, nz);
        addWind(nx, ny, nz, wx, wy, wz, strength, fx[i], fy[i], fz[i]);
    }
}

template <typename T, bool kSymplectic>
void euler(const EulerRow<T>& r, int n) {
    T* __restrict px = r.xOut.x;
    T* __restrict py = r.xOut.y;
    T* __restrict pz = r.xOut.z;
    T* __restrict vx = r.v.x;
    T* __restrict vy = r.v.y;
    T* __restrict vz = r.v.z;
    const T h = r.h, mu = r.damping, w = r.inverseMass;
    for (int i = 0; i < n; ++i) {
        T x = r.xIn.x[i], y = r.xIn.y[i], z = r.xIn.z[i];
        T u = vx[i], v = vy[i], s = vz[i];
        eulerComponent<T, kSymplectic>(x, u, r.f.x[i], h, mu, w, r.gx);
        eulerComponent<T, kSymplectic>(y, v, r.f.y[i], h, mu, w, r.gy);
        eulerComponent<T, kSymplectic>(z, s, r.f.z[i], h, mu, w, r.gz);
        px[i] = x;
        py[i] = y;
        pz[i] = z;
        vx[i] = u;
        vy[i] = v;
        vz[i] = s;
    }
}

template <typename T>
bool anyBad(ConstRow3<T> x, ConstRow3<T> v, T maxSpeed2, int n) {
    int bad = 0;
    for (int i = 0; i < n; ++i)
        bad |= int(badVertex(x.x[i], x.y[i], x.z[i], v.x[i], v.y[i], v.z[i], maxSpeed2));
    return bad != 0;
}

}  // namespace

template <typename T>
const RowKernels<T>& rowKernels() {
    static const RowKernels<T> kernels{&coefficients<T>, &accumulate<T>,  &wind<T>,
                                       &euler<T, false>, &euler<T, true>, &anyBad<T>};
    return kernels;
}
template const RowKernels<float>& rowKernels();
template const RowKernels<double>& rowKernels();

}  // namespace cloth::CLOTH_ISA_NS
