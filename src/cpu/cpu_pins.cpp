// The CPU backend's pins: the viewer's setPinned, and the pins that follow a moving collider
// (model/pin_follow.h), posed at the end of each step with the colliders (docs/colliders.md §8).
#include <algorithm>
#include <stdexcept>

#include "cpu/cpu_solver.h"

namespace cloth {

// A vertex already following a collider keeps following it when pinned again (the viewer
// re-pins the scene's pins after a backend switch); released, it stops following.
template <typename T>
void CpuSolver<T>::setPinned(int i, int j, bool pinned) {
    if (!grid_.contains(i, j)) throw std::invalid_argument("setPinned: vertex outside the grid");
    const std::int64_t k = grid_.index(i, j);
    pinned_[k] = pinned ? 1 : 0;
    pinPosition_[k] = x_.get(k);
    if (pinned) v_.set(k, pinVelocity(k));
    const auto at = std::lower_bound(pinList_.begin(), pinList_.end(), k);
    if (pinned && (at == pinList_.end() || *at != k)) pinList_.insert(at, k);
    if (!pinned && at != pinList_.end() && *at == k) pinList_.erase(at);
    if (!pinned) {
        std::erase_if(follows_, [k](const FollowPin& f) { return f.vertex == k; });
        if (!pinVelocity_.empty()) pinVelocity_[std::size_t(k)] = Vec3<T>(0);
    }
    forcesValid_ = false;
}

// The scene's follow pins start at their pose at t = 0, with its velocity.
template <typename T>
void CpuSolver<T>::takeFollowPins(const Scene& scene) {
    follows_ = followPins(scene);
    pinVelocity_.clear();
    if (follows_.empty()) return;
    pinVelocity_.assign(std::size_t(grid_.count()), Vec3<T>(0));
    poseFollowPins(0.0);
    for (const FollowPin& f : follows_) {
        x_.set(f.vertex, pinPosition_[std::size_t(f.vertex)]);
        v_.set(f.vertex, pinVelocity_[std::size_t(f.vertex)]);
    }
}

template <typename T>
bool CpuSolver<T>::samePins(const Scene& scene) const {
    std::vector<std::uint8_t> pinned(std::size_t(grid_.count()), 0);
    for (const Pin& p : scene.pins) pinned[std::size_t(grid_.index(p.i, p.j))] = 1;
    if (pinned != pinned_) return false;
    const std::vector<FollowPin> follows = followPins(scene);
    return std::equal(follows.begin(), follows.end(), follows_.begin(), follows_.end(),
                      [](const FollowPin& a, const FollowPin& b) {
                          return a.vertex == b.vertex && a.collider == b.collider;
                      });
}

template <typename T>
void CpuSolver<T>::poseFollowPins(double t) noexcept {
    for (const FollowPin& f : follows_) {
        const PinState s = followPinAt(f, t);
        pinPosition_[std::size_t(f.vertex)] = Vec3<T>(s.position);
        pinVelocity_[std::size_t(f.vertex)] = Vec3<T>(s.velocity);
    }
}

// cpu_solver.h declares the class instantiations extern: this file's members are instantiated
// here, the rest in cpu_solver.cpp.
#define CLOTH_INSTANTIATE(T)                                  \
    template void CpuSolver<T>::setPinned(int, int, bool);    \
    template void CpuSolver<T>::takeFollowPins(const Scene&); \
    template bool CpuSolver<T>::samePins(const Scene&) const; \
    template void CpuSolver<T>::poseFollowPins(double) noexcept;
CLOTH_INSTANTIATE(float)
CLOTH_INSTANTIATE(double)
#undef CLOTH_INSTANTIATE

}  // namespace cloth
