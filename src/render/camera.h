// An orbit camera (target, yaw, pitch, distance) and the ray maths the viewer picks with.
// No GL: the matrices are glm, the picking is plain geometry.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace cloth::render {

struct Bounds {
    glm::vec3 lo{1e30f}, hi{-1e30f};
    void add(const glm::vec3& p);
    void add(const Bounds& b);
    bool empty() const { return lo.x > hi.x; }
    glm::vec3 centre() const { return 0.5f * (lo + hi); }
    float radius() const { return 0.5f * glm::length(hi - lo); }
};

struct Ray {
    glm::vec3 origin, direction;  // direction is unit length
};

class Camera {
public:
    float yaw = 0.6f;     // about +y [rad], 0 looks along −z
    float pitch = 0.45f;  // above the horizon [rad]
    float distance = 3;   // eye to target [m]
    glm::vec3 target{0, 0.5f, 0};
    float fovY = 0.7854f;  // vertical field of view [rad]

    glm::vec3 eye() const;
    glm::vec3 forward() const;  // unit, eye → target
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;

    // Mouse motion in pixels of a viewport `height` pixels tall.
    void orbit(float dxPixels, float dyPixels);
    void pan(float dxPixels, float dyPixels, float height);
    void zoom(float wheelSteps);  // positive: closer
    // Looks at `b` from the current direction so that it fills a view `aspect` = width / height:
    // its bounding sphere just fits the narrower of the two fields of view.
    void frame(const Bounds& b, float aspect);

    // The ray through normalised device coordinates (x, y in [−1, 1], y up).
    Ray ray(const glm::vec2& ndc, float aspect) const;
};

// The index of the point nearest to the ray (perpendicular distance, in front of the origin)
// whose distance is below `maxAngle` radians as seen from the ray's origin; nullopt if none.
std::optional<std::int64_t> nearestToRay(const Ray& ray, const std::vector<glm::dvec3>& points,
                                         float maxAngle = 0.03f);

// Where the ray meets the plane through `point` with normal `normal`; nullopt if parallel or
// behind the origin.
std::optional<glm::vec3> intersectPlane(const Ray& ray, const glm::vec3& point,
                                        const glm::vec3& normal);

}  // namespace cloth::render
