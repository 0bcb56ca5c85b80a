#include "render/collider_pick.h"

#include <algorithm>
#include <cmath>

namespace cloth::render {
namespace {

constexpr double kHitDistance = 1e-4;  // [m]: closer than this to the surface is a hit
constexpr int kMaxSteps = 400;

// The ray parameters [enter, leave] inside the box lo..hi (slab method), empty if it misses.
bool clipToBox(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi,
               double& enter, double& leave) {
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-300) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
    }
    return enter <= leave;
}

// The first t in [t, tEnd] where φ(o + t d) < kHitDistance, marching by φ·stepScale.
template <typename Shape>
std::optional<double> march(const Shape& s, const glm::dvec3& o, const glm::dvec3& d, double t,
                            double tEnd, double stepScale) {
    for (int k = 0; k < kMaxSteps && t <= tEnd; ++k) {
        const double phi = contact(s, o + t * d).phi;
        if (phi < kHitDistance) return t;
        t += std::max(phi * stepScale, 0.5 * kHitDistance);
    }
    return std::nullopt;
}

template <typename Shape>
std::optional<double> hitDistance(const Shape& s, const glm::dvec3& o, const glm::dvec3& d,
                                  double tMax) {
    return march(s, o, d, 0.0, tMax, 1.0);
}

// A grid: march only inside its box (outside it the clamped φ is no distance bound).
std::optional<double> hitDistance(const SdfColliderT<double>& s, const glm::dvec3& o,
                                  const glm::dvec3& d, double tMax) {
    const glm::dmat3 toGrid = glm::transpose(s.rotation);
    const glm::dvec3 lo = s.grid->origin, hi = lo + s.grid->cell * glm::dvec3(s.grid->count - 1);
    double enter = 0, leave = tMax;
    if (!clipToBox(toGrid * (o - s.translation), toGrid * d, lo, hi, enter, leave))
        return std::nullopt;
    return march(s, o, d, enter, leave, 1 / std::sqrt(3.0));
}

}  // namespace

std::optional<ColliderHit> pickCollider(const Ray& ray, const std::vector<Collider>& colliders,
                                        double time, const std::vector<ColliderDrag>& drags,
                                        double maxDistance) {
    const glm::dvec3 o(ray.origin), d = glm::normalize(glm::dvec3(ray.direction));
    std::optional<ColliderHit> best;
    for (std::size_t k = 0; k < colliders.size(); ++k) {
        if (colliders[k].as<Plane>() != nullptr) continue;
        const ShapeD shape = posedShape(colliders[k], time, k < drags.size() ? &drags[k] : nullptr);
        const double limit = best ? best->distance : maxDistance;
        const auto t =
            std::visit([&](const auto& s) { return hitDistance(s, o, d, limit); }, shape);
        if (t && *t <= limit) best = ColliderHit{k, o + *t * d, *t};
    }
    return best;
}

std::optional<glm::dvec3> dragTarget(const Ray& ray, const glm::dvec3& pickedPoint,
                                     const glm::dvec3& planeNormal, const glm::dvec3& startOffset) {
    const auto hit = intersectPlane(ray, glm::vec3(pickedPoint), glm::vec3(planeNormal));
    if (!hit) return std::nullopt;
    return startOffset + (glm::dvec3(*hit) - pickedPoint);
}

}  // namespace cloth::render
