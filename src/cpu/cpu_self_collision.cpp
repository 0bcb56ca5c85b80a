#include "cpu/cpu_self_collision.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cloth {
namespace {

// Corrections bring a contact's gap to h; one still closer than h·(1 − kSlack) counts again.
// The slack ends the iterations once every contact holds, instead of chasing rounding.
constexpr double kSlack = 0.01;

std::uint32_t hashCell(const glm::ivec3& c, std::uint32_t mask) {
    // Teschner et al. 2003, "Optimized spatial hashing for collision detection".
    return ((std::uint32_t(c.x) * 73856093u) ^ (std::uint32_t(c.y) * 19349663u) ^
            (std::uint32_t(c.z) * 83492791u)) &
           mask;
}

}  // namespace

template <typename T>
CpuSelfCollision<T>::CpuSelfCollision(const Grid& grid, const SelfCollision& spec)
    : nu_(grid.nu), nv_(grid.nv) {
    setParameters(spec);
    const std::size_t n = std::size_t(grid.count());
    for (auto* a : {&y_, &ref_, &z_, &step_, &delta_}) a->assign(n, Vec3<T>(0));
    touches_.assign(n, 0);
    inContact_.assign(n, 0);
    cellOf_.assign(n, glm::ivec3(0));
    boxLow_.assign(n, Vec3<T>(0));
    boxHigh_.assign(n, Vec3<T>(0));
    bucketOf_.assign(n, 0);
    sorted_.assign(n, 0);
    // A table of at least twice as many buckets as vertices: few vertices of different cells
    // share one.
    std::uint32_t buckets = 1;
    while (buckets < 2 * n) buckets *= 2;
    mask_ = buckets - 1;
    bucketStart_.assign(std::size_t(buckets) + 1, 0);
    cursor_.assign(buckets, 0);
}

template <typename T>
void CpuSelfCollision<T>::setParameters(const SelfCollision& spec) {
    thickness_ = T(spec.thickness);
    friction_ = T(spec.friction);
}

// The cell size covers every pair within reach of each other: an element lies within L (its
// longest owned edge) of its owner, so a point within h of a triangle is within h + L of the
// triangle's owner, and two edges within h are owned by vertices within h + 2L.
template <typename T>
void CpuSelfCollision<T>::buildCells() {
    const std::int64_t n = std::int64_t(y_.size());
    T longest = 0;
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i)
            for (const GridOffset& e : kOwnedEdgeEnds)
                if (i + e.di < nu_ && j + e.dj < nv_) {
                    const Vec3<T> d = y_[std::size_t(std::int64_t(j + e.dj) * nu_ + i + e.di)] -
                                      y_[std::size_t(std::int64_t(j) * nu_ + i)];
                    longest = std::max(longest, glm::dot(d, d));
                }
    reach_ = std::sqrt(longest);
    // Each owner's box: its quad's corners (those that exist), grown by h. Two owners whose
    // boxes miss each other have no contact, nor does a point outside an owner's box.
    for (int j = 0; j < nv_; ++j)
        for (int i = 0; i < nu_; ++i) {
            const std::size_t k = std::size_t(std::int64_t(j) * nu_ + i);
            Vec3<T> low = y_[k], high = y_[k];
            for (const GridOffset& e : kOwnedEdgeEnds)
                if (i + e.di < nu_ && j + e.dj < nv_) {
                    const Vec3<T> c = y_[std::size_t(std::int64_t(j + e.dj) * nu_ + i + e.di)];
                    low = glm::min(low, c);
                    high = glm::max(high, c);
                }
            boxLow_[k] = low - T(0.5) * thickness_;
            boxHigh_[k] = high + T(0.5) * thickness_;
        }
    cell_ = thickness_ + T(2) * reach_;
    std::fill(bucketStart_.begin(), bucketStart_.end(), 0u);
    for (std::int64_t k = 0; k < n; ++k) {  // count
        const Vec3<T> c = glm::floor(y_[std::size_t(k)] / cell_);
        // A non-finite position lands in cell 0; the step's instability check reports it.
        const glm::ivec3 cell = glm::all(glm::lessThan(glm::abs(c), Vec3<T>(1e9)))
                                    ? glm::ivec3(c)
                                    : glm::ivec3(0);
        cellOf_[std::size_t(k)] = cell;
        bucketOf_[std::size_t(k)] = hashCell(cell, mask_);
        ++bucketStart_[bucketOf_[std::size_t(k)] + 1];
    }
    for (std::size_t b = 1; b < bucketStart_.size(); ++b)  // prefix sum
        bucketStart_[b] += bucketStart_[b - 1];
    // Scatter, a running cursor per bucket: the vertices of a bucket in index order.
    std::copy(bucketStart_.begin(), bucketStart_.end() - 1, cursor_.begin());
    for (std::int64_t k = 0; k < n; ++k) sorted_[cursor_[bucketOf_[std::size_t(k)]]++] = k;
}

template <typename T>
void CpuSelfCollision<T>::addContact(const ContactGeometry<T>& g,
                                     const std::array<std::int64_t, 4>& vertex, int count,
                                     int& contacts) {
    if (!(g.gap < thickness_ * T(1 - kSlack))) return;
    std::array<T, 4> w{};
    Vec3<T> slip(0);
    for (int j = 0; j < count; ++j) {
        const std::size_t k = std::size_t(vertex[j]);
        w[j] = (*pinned_)[k] ? T(0) : (*inverseMass_)[k];
        slip += g.alpha[j] * (y_[k] - z_[k]);
    }
    std::array<Vec3<T>, 4> dx;
    if (!contactCorrection(g, w, count, slip, thickness_, friction_, dx)) return;
    ++contacts;
    for (int j = 0; j < count; ++j) {
        delta_[std::size_t(vertex[j])] += dx[j];
        ++touches_[std::size_t(vertex[j])];
    }
}

// Point p against the triangles vertex q owns (those that share no vertex with it).
template <typename T>
void CpuSelfCollision<T>::pointAgainstTriangles(std::int64_t p, std::int64_t q, int& contacts) {
    const int qi = int(q % nu_), qj = int(q / nu_);
    if (qi + 1 >= nu_ || qj + 1 >= nv_) return;  // the last row and column own no triangle
    // A point within h of q's elements lies within h/2 of q's box (grown by h/2 already).
    const Vec3<T> point = y_[std::size_t(p)], half(T(0.5) * thickness_);
    if (glm::any(glm::lessThan(point + half, boxLow_[std::size_t(q)])) ||
        glm::any(glm::lessThan(boxHigh_[std::size_t(q)] + half, point)))
        return;
    for (const auto& tri : kOwnedTriangles) {
        std::array<std::int64_t, 4> v{p, 0, 0, 0};
        for (int c = 0; c < 3; ++c) v[c + 1] = std::int64_t(qj + tri[c].dj) * nu_ + qi + tri[c].di;
        if (p == v[1] || p == v[2] || p == v[3]) continue;
        const auto pos = [&](int c) { return y_[std::size_t(v[c])]; };
        const auto ref = [&](int c) { return ref_[std::size_t(v[c])]; };
        const T side = pointTriangleSide(ref(0), ref(1), ref(2), ref(3));
        ContactGeometry<T> g;
        if (pointTriangle(pos(0), pos(1), pos(2), pos(3), side, g) && std::abs(g.gap) < thickness_)
            addContact(g, v, 4, contacts);
    }
}

// The contacts between the elements of owners p < q: each point against the other's
// triangles, and edge against edge. Elements that share a vertex are skipped
// (model/self_contact.h).
template <typename T>
void CpuSelfCollision<T>::visitOwners(std::int64_t p, std::int64_t q, int& contacts) {
    // Elements of two owners within h have boxes (grown by h/2 each) that overlap.
    if (glm::any(glm::lessThan(boxHigh_[std::size_t(p)], boxLow_[std::size_t(q)])) ||
        glm::any(glm::lessThan(boxHigh_[std::size_t(q)], boxLow_[std::size_t(p)])))
        return;
    pointAgainstTriangles(p, q, contacts);
    pointAgainstTriangles(q, p, contacts);
    const int qi = int(q % nu_), qj = int(q / nu_), pi = int(p % nu_), pj = int(p / nu_);
    const auto at = [this](int i, int j) { return std::int64_t(j) * nu_ + i; };
    for (const GridOffset& ep : kOwnedEdgeEnds) {
        if (pi + ep.di >= nu_ || pj + ep.dj >= nv_) continue;
        const std::int64_t p1 = at(pi + ep.di, pj + ep.dj);
        const Vec3<T> pa = y_[std::size_t(p)], pb = y_[std::size_t(p1)];
        for (const GridOffset& eq : kOwnedEdgeEnds) {
            if (qi + eq.di >= nu_ || qj + eq.dj >= nv_) continue;
            const std::int64_t q1 = at(qi + eq.di, qj + eq.dj);
            if (p1 == q || p1 == q1 || p == q1) continue;  // (p ≠ q: p < q)
            const Vec3<T> qa = y_[std::size_t(q)], qb = y_[std::size_t(q1)];
            // The edges' own boxes, grown by h, first.
            if (glm::any(glm::lessThan(glm::max(pa, pb) + thickness_, glm::min(qa, qb))) ||
                glm::any(glm::lessThan(glm::max(qa, qb) + thickness_, glm::min(pa, pb))))
                continue;
            const std::array<std::int64_t, 4> v{p, p1, q, q1};
            const auto ref = [&](int c) { return ref_[std::size_t(v[c])]; };
            const Vec3<T> refCross = glm::cross(ref(1) - ref(0), ref(3) - ref(2));
            const T side = sideOf(glm::dot(refCross, ref(0) - ref(2)));
            ContactGeometry<T> g;
            if (edgeEdge(pa, pb, qa, qb, side, refCross, g) && std::abs(g.gap) < thickness_)
                addContact(g, v, 4, contacts);
        }
    }
}

template <typename T>
int CpuSelfCollision<T>::correct() {
    buildCells();
    std::fill(delta_.begin(), delta_.end(), Vec3<T>(0));
    std::fill(touches_.begin(), touches_.end(), 0);
    int contacts = 0;
    const std::int64_t n = std::int64_t(y_.size());
    for (std::int64_t p = 0; p < n; ++p) {
        const glm::ivec3 home = cellOf_[std::size_t(p)];
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const glm::ivec3 cell = home + glm::ivec3(dx, dy, dz);
                    const std::uint32_t b = hashCell(cell, mask_);
                    for (std::uint32_t s = bucketStart_[b]; s < bucketStart_[b + 1]; ++s) {
                        const std::int64_t q = sorted_[s];
                        // Buckets mix cells: only q's own cell counts, so no pair is seen twice.
                        if (p < q && cellOf_[std::size_t(q)] == cell) visitOwners(p, q, contacts);
                    }
                }
    }
    // Jacobi with averaging: each vertex takes the mean of its contacts' corrections.
    for (std::size_t k = 0; k < y_.size(); ++k)
        if (touches_[k] > 0) {
            y_[k] += delta_[k] / T(touches_[k]);
            inContact_[k] = 1;
        }
    return contacts;
}

template <typename T>
void CpuSelfCollision<T>::resolve(const Soa3<T>& start, Soa3<T>& x, Soa3<T>& v,
                                  const AlignedVector<T>& inverseMass,
                                  const std::vector<std::uint8_t>& pinned, T dt,
                                  const std::function<void(Vec3<T>&)>& collide) {
    const std::size_t n = y_.size();
    inverseMass_ = &inverseMass;
    pinned_ = &pinned;
    // The substeps (docs/physics.md "Self-collision", the step bound): every vertex's motion
    // differs from the common one by at most R, so two elements approach by at most 2R over
    // the step, 2R/m per substep; m > 4R/h keeps that below h/2, the separation each substep
    // leaves, and no pair can meet within a substep unseen.
    Vec3<T> low(std::numeric_limits<T>::max()), high(std::numeric_limits<T>::lowest());
    for (std::size_t k = 0; k < n; ++k) {
        step_[k] = x.get(std::int64_t(k)) - start.get(std::int64_t(k));
        low = glm::min(low, step_[k]);
        high = glm::max(high, step_[k]);
    }
    const Vec3<T> middle = T(0.5) * (low + high);
    T radius = 0;
    for (std::size_t k = 0; k < n; ++k) radius = std::max(radius, glm::length(step_[k] - middle));
    const double needed = std::ceil(4.0 * double(radius) / double(thickness_));
    int substeps = std::isfinite(needed) ? int(std::clamp(needed, 1.0, double(kMaxSubsteps)))
                                         : kMaxSubsteps;
    ++stats_.steps;
    stats_.stepsOverBound += !(needed <= double(kMaxSubsteps));
    stats_.substeps += substeps;
    stats_.mostSubsteps = std::max(stats_.mostSubsteps, substeps);
    std::fill(inContact_.begin(), inContact_.end(), 0);
    for (std::size_t k = 0; k < n; ++k) y_[k] = start.get(std::int64_t(k));
    for (int s = 1; s <= substeps; ++s) {
        z_ = y_;
        const T share = T(1) / T(substeps);
        for (std::size_t k = 0; k < n; ++k) {
            y_[k] += share * step_[k];
            if (pinned[k]) y_[k] = x.get(std::int64_t(k));  // pins sit at their end pose
        }
        ref_ = y_;
        for (int it = 0; it < kIterations; ++it) {
            const int found = correct();
            ++stats_.iterations;
            stats_.contacts += found;
            if (it == 0 && s == substeps) stats_.lastContacts = found;
            if (found == 0) break;
            for (std::size_t k = 0; k < n; ++k)
                if (touches_[k] > 0) collide(y_[k]);
        }
    }
    const T rate = T(1) / dt;
    for (std::size_t k = 0; k < n; ++k) {
        const std::int64_t i = std::int64_t(k);
        const Vec3<T> change = y_[k] - x.get(i);
        if (change == Vec3<T>(0)) continue;
        x.set(i, y_[k]);
        v.set(i, v.get(i) + rate * change);
    }
}

template class CpuSelfCollision<float>;
template class CpuSelfCollision<double>;

}  // namespace cloth
