#include "cpu/cpu_self_collision.h"

#include <algorithm>
#include <atomic>
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
    for (auto* a : {&y_, &ref_, &z_, &step_}) a->assign(n, Vec3<T>(0));
    sum_.assign(3 * n, 0);
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
    // The fixed point's unit: a power of two such that 64 contacts (kMostTouches) of ±4h each
    // fit in 31 bits (1 nm at h = 4 mm, below a float position's rounding at 1 m).
    fixedScale_ = T(std::exp2(std::floor(std::log2(double(1u << 31) / (256.0 * spec.thickness)))));
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
        const glm::ivec3 cell =
            glm::all(glm::lessThan(glm::abs(c), Vec3<T>(1e9))) ? glm::ivec3(c) : glm::ivec3(0);
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
    // Summed in fixed point with integer atomics: the same sum in any order, so any number of
    // threads (and a GPU's work groups) get the same bits. A correction is clamped to ±4h
    // (a contact's is at most 2h along the normal plus its friction).
    const T limit = T(4) * thickness_;
    for (int j = 0; j < count; ++j) {
        const std::size_t k = std::size_t(vertex[j]);
        for (int c = 0; c < 3; ++c) {
            const T fixed = std::round(std::clamp(dx[j][c], -limit, limit) * fixedScale_);
            std::atomic_ref<std::int32_t>(sum_[3 * k + std::size_t(c)])
                .fetch_add(std::int32_t(fixed), std::memory_order_relaxed);
        }
        std::atomic_ref<std::int32_t>(touches_[k]).fetch_add(1, std::memory_order_relaxed);
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

// One Jacobi iteration, thread `t` of `threads` taking the points of its range.
template <typename T>
int CpuSelfCollision<T>::correct(int t, int threads, const std::function<void()>& sync) {
    const std::int64_t n = std::int64_t(y_.size());
    const std::int64_t begin = n * t / threads, end = n * (t + 1) / threads;
    if (t == 0) {
        buildCells();
        contacts_ = 0;
    }
    std::fill(sum_.begin() + 3 * begin, sum_.begin() + 3 * end, 0);
    std::fill(touches_.begin() + begin, touches_.begin() + end, 0);
    sync();
    int contacts = 0;
    for (std::int64_t p = begin; p < end; ++p) {
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
    std::atomic_ref<int>(contacts_).fetch_add(contacts, std::memory_order_relaxed);
    std::int64_t crowded = -1;
    for (std::int64_t k = begin; k < end && crowded < 0; ++k)
        if (touches_[std::size_t(k)] > kMostTouches) crowded = k;
    crowdedBy_[std::size_t(t)] = crowded;
    sync();
    for (const std::int64_t c : crowdedBy_) {  // the lowest: threads take ranges in order
        if (c < 0) continue;
        if (t == 0) {
            crowded_ = c;
            crowdedTouches_ = touches_[std::size_t(c)];
        }
        return -1;  // its sums may have overflowed: nothing of them is applied
    }
    // Jacobi with averaging: each vertex takes the mean of its contacts' corrections.
    for (std::int64_t k = begin; k < end; ++k) {
        const std::size_t i = std::size_t(k);
        if (touches_[i] == 0) continue;
        const Vec3<T> sum{T(sum_[3 * i]), T(sum_[3 * i + 1]), T(sum_[3 * i + 2])};
        y_[i] += sum / (fixedScale_ * T(touches_[i]));
        inContact_[i] = 1;
        (*collide_)(y_[i]);
    }
    const int found = contacts_;
    sync();
    return found;
}

template <typename T>
bool CpuSelfCollision<T>::resolve(const Soa3<T>& start, Soa3<T>& x, Soa3<T>& v,
                                  const AlignedVector<T>& inverseMass,
                                  const std::vector<std::uint8_t>& pinned, T dt,
                                  const std::function<void(Vec3<T>&)>& collide, int t, int threads,
                                  const std::function<void()>& sync) {
    const std::int64_t n = std::int64_t(y_.size());
    const std::int64_t begin = n * t / threads, end = n * (t + 1) / threads;
    if (t == 0) {
        inverseMass_ = &inverseMass;
        pinned_ = &pinned;
        collide_ = &collide;
        crowdedBy_.assign(std::size_t(threads), -1);
        crowded_ = -1;
        chooseSubsteps(start, x);
    }
    sync();
    const int substeps = substeps_;
    const T share = T(1) / T(substeps);
    for (std::int64_t k = begin; k < end; ++k) {
        y_[std::size_t(k)] = start.get(k);
        inContact_[std::size_t(k)] = 0;
    }
    for (int s = 1; s <= substeps; ++s) {
        for (std::int64_t k = begin; k < end; ++k) {
            const std::size_t i = std::size_t(k);
            z_[i] = y_[i];
            y_[i] += share * step_[i];
            if (pinned[i]) y_[i] = x.get(k);  // pins sit at their end pose
            ref_[i] = y_[i];
        }
        sync();
        for (int it = 0; it < kIterations; ++it) {
            const int found = correct(t, threads, sync);
            if (found < 0) return false;  // every thread saw the same crowded vertex
            if (t == 0) {
                ++stats_.iterations;
                stats_.contacts += found;
                if (it == 0 && s == substeps) stats_.lastContacts = found;
            }
            if (found == 0) break;  // every thread read the same count before the last sync
        }
    }
    const T rate = T(1) / dt;
    for (std::int64_t k = begin; k < end; ++k) {
        const Vec3<T> change = y_[std::size_t(k)] - x.get(k);
        if (change == Vec3<T>(0)) continue;
        x.set(k, y_[std::size_t(k)]);
        v.set(k, v.get(k) + rate * change);
    }
    sync();
    return true;
}

// The substeps (docs/physics.md "Self-collision", the step bound): every vertex's motion lies
// within R of the middle of the motions' bounding box, R at most half its diagonal, so two
// elements approach by at most 2R over the step, 2R/m per substep; m > 4R/h keeps that below
// h/2, the separation each substep leaves, and no pair can meet within a substep unseen.
template <typename T>
void CpuSelfCollision<T>::chooseSubsteps(const Soa3<T>& start, const Soa3<T>& x) {
    Vec3<T> low(std::numeric_limits<T>::max()), high(std::numeric_limits<T>::lowest());
    for (std::size_t k = 0; k < step_.size(); ++k) {
        step_[k] = x.get(std::int64_t(k)) - start.get(std::int64_t(k));
        low = glm::min(low, step_[k]);
        high = glm::max(high, step_[k]);
    }
    const double radius = 0.5 * double(glm::length(high - low));
    const double needed = std::ceil(4.0 * radius / double(thickness_));
    substeps_ =
        std::isfinite(needed) ? int(std::clamp(needed, 1.0, double(kMaxSubsteps))) : kMaxSubsteps;
    ++stats_.steps;
    stats_.stepsOverBound += !(needed <= double(kMaxSubsteps));
    stats_.substeps += substeps_;
    stats_.mostSubsteps = std::max(stats_.mostSubsteps, substeps_);
}

template <typename T>
std::string CpuSelfCollision<T>::crowdedReason() const {
    return selfCollapseReason(int(crowded_ % nu_), int(crowded_ / nu_), crowdedTouches_);
}

template class CpuSelfCollision<float>;
template class CpuSelfCollision<double>;

}  // namespace cloth
