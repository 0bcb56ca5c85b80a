// Structure-of-arrays storage of the CPU backend: one array per component, 64-byte aligned, so a
// row of x (or y, or z) is contiguous and the row kernels (cpu/cpu_rows.h) load it in vectors.
#pragma once

#include <cstdint>
#include <new>
#include <vector>

#include "cpu/cpu_rows.h"
#include "model/grid.h"

namespace cloth {

// Cache-line aligned allocation: vector loads start on a line, and no two threads' arrays share
// one.
template <typename T>
struct AlignedAllocator {
    using value_type = T;
    static constexpr std::align_val_t kAlign{64};
    AlignedAllocator() = default;
    template <typename U>
    AlignedAllocator(const AlignedAllocator<U>&) {}  // NOLINT: rebinding
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
    // The unsized form: clang enables sized deallocation only with -fsized-deallocation.
    void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
    template <typename U>
    bool operator==(const AlignedAllocator<U>&) const {
        return true;
    }
};
template <typename T>
using AlignedVector = std::vector<T, AlignedAllocator<T>>;

template <typename T>
struct Soa3 {
    AlignedVector<T> x, y, z;

    void assign(std::int64_t n, const Vec3<T>& value) {
        x.assign(std::size_t(n), value.x);
        y.assign(std::size_t(n), value.y);
        z.assign(std::size_t(n), value.z);
    }
    std::int64_t size() const { return std::int64_t(x.size()); }
    Vec3<T> get(std::int64_t k) const { return {x[k], y[k], z[k]}; }
    void set(std::int64_t k, const Vec3<T>& p) {
        x[k] = p.x;
        y[k] = p.y;
        z[k] = p.z;
    }
    Row3<T> row(std::int64_t k) { return {x.data() + k, y.data() + k, z.data() + k}; }
    ConstRow3<T> row(std::int64_t k) const { return {x.data() + k, y.data() + k, z.data() + k}; }
};

// stiffnessProduct (model/stiffness.h) reads positions through this.
template <typename T>
Vec3<T> positionAt(const Soa3<T>& x, std::int64_t k) {
    return x.get(k);
}

}  // namespace cloth
