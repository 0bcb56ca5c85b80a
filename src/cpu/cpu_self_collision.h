// Self-collision in the CPU backend (docs/physics.md "Self-collision"): after each step, the
// motion from the step's start to the integrator's result is replayed in substeps short enough
// that no element can pass through another unseen, and after each the non-neighbouring
// elements closer than the thickness are pushed apart by Jacobi iterations of position
// corrections (model/self_contact.h). The candidates come from a spatial hash built by counting
// sort (count per cell, exclusive prefix sum, scatter), as a GPU builds it; each vertex visits
// its 27 cells.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "cpu/cpu_soa.h"
#include "model/scene.h"
#include "model/self_contact.h"
#include "solver/solver.h"

namespace cloth {

template <typename T>
class CpuSelfCollision {
public:
    // Each substep's corrections stop after this many Jacobi iterations, or earlier at the
    // first that finds no contact (the rest would change nothing).
    static constexpr int kIterations = 16;
    // A step is replayed in at most this many substeps; one that needs more is counted in
    // SelfCollisionStats::stepsOverBound.
    static constexpr int kMaxSubsteps = 256;
    // The fixed point holds the sum of this many contacts a vertex (setParameters); with more,
    // resolve() stops and names the vertex (crowded(); model/self_contact.h).
    static constexpr int kMostTouches = kSelfMostTouches;

    CpuSelfCollision() = default;
    CpuSelfCollision(const Grid& grid, const SelfCollision& spec);
    bool active() const { return thickness_ > T(0); }
    void setParameters(const SelfCollision& spec);

    // One step from the positions `start` to x (the integrator's result, pins and colliders
    // applied): x moves out of contact and v by the same change over dt. collide(p): the
    // colliders' position projection, applied to the moved vertices. Called by each of
    // `threads` threads (t = 0 … threads − 1) at once, sync() a barrier between them; the
    // result has the same bits for any number of threads. False where a vertex was in more than
    // kMostTouches contacts at once: x and v are left as the integrator left them.
    bool resolve(const Soa3<T>& start, Soa3<T>& x, Soa3<T>& v, const AlignedVector<T>& inverseMass,
                 const std::vector<std::uint8_t>& pinned, T dt,
                 const std::function<void(Vec3<T>&)>& collide, int t, int threads,
                 const std::function<void()>& sync);
    const SelfCollisionStats& stats() const { return stats_; }
    // 1 for the vertices in a contact in the last step's corrections.
    const std::vector<std::uint8_t>& inContact() const { return inContact_; }
    // After resolve() returned false: the lowest vertex in too many contacts (else −1).
    std::int64_t crowded() const { return crowded_; }
    // The reason a run reports for it (docs/physics.md "Self-collision").
    std::string crowdedReason() const;

private:
    void buildCells();  // the spatial hash of y_
    void chooseSubsteps(const Soa3<T>& start, const Soa3<T>& x);
    // One Jacobi iteration over y_, thread t's share; the contacts all threads corrected, or −1
    // (every thread) where a vertex is in more than kMostTouches.
    int correct(int t, int threads, const std::function<void()>& sync);
    void visitOwners(std::int64_t p, std::int64_t q, int& contacts);
    void pointAgainstTriangles(std::int64_t p, std::int64_t q, int& contacts);
    void addContact(const ContactGeometry<T>& g, const std::array<std::int64_t, 4>& vertex,
                    int count, int& contacts);

    int nu_ = 0, nv_ = 0;
    T thickness_ = 0, friction_ = 0;
    T cell_ = 0, reach_ = 0;  // the hash's cell size; the longest owned edge L
    // y_: positions being corrected; ref_: where the substep's motion took them (the sides);
    // z_: the substep's start (the slip friction acts on); target_: the integrator's result.
    std::vector<Vec3<T>> y_, ref_, z_, step_;
    // One iteration's corrections per vertex (x, y, z), summed in fixed point: units of
    // 1/fixedScale_ m. And the contacts per vertex.
    std::vector<std::int32_t> sum_, touches_;
    T fixedScale_ = 0;
    int substeps_ = 1;
    int contacts_ = 0;  // an iteration's contacts, summed over the threads (atomic_ref)
    std::vector<std::int64_t> crowdedBy_;  // per thread: its first crowded vertex, or −1
    std::int64_t crowded_ = -1;
    int crowdedTouches_ = 0;
    std::vector<std::uint8_t> inContact_;
    // The spatial hash: cell of each vertex, its bucket, the buckets' starts (counting sort)
    // and the vertices sorted by bucket.
    std::vector<glm::ivec3> cellOf_;
    std::vector<Vec3<T>> boxLow_, boxHigh_;  // each owner's elements' box, grown by h/2
    std::vector<std::uint32_t> bucketOf_, bucketStart_, cursor_;
    std::vector<std::int64_t> sorted_;
    std::uint32_t mask_ = 0;
    // resolve()'s inverse masses and pins (a pinned vertex's correction weight is 0).
    const AlignedVector<T>* inverseMass_ = nullptr;
    const std::vector<std::uint8_t>* pinned_ = nullptr;
    const std::function<void(Vec3<T>&)>* collide_ = nullptr;
    SelfCollisionStats stats_;
};

extern template class CpuSelfCollision<float>;
extern template class CpuSelfCollision<double>;

}  // namespace cloth
