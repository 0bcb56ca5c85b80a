#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace cloth::render {
namespace {

constexpr float kMaxPitch = 1.55f;  // just short of straight down or up, where yaw is lost
constexpr float kOrbitPerPixel = 0.008f;
constexpr float kZoomPerStep = 0.9f;

}  // namespace

void Bounds::add(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
}

void Bounds::add(const Bounds& b) {
    if (b.empty()) return;
    add(b.lo);
    add(b.hi);
}

glm::vec3 Camera::forward() const {
    return -glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                      std::cos(pitch) * std::cos(yaw));
}

glm::vec3 Camera::eye() const {
    return target - distance * forward();
}

glm::mat4 Camera::view() const {
    return glm::lookAt(eye(), target, glm::vec3(0, 1, 0));
}

glm::mat4 Camera::projection(float aspect) const {
    const float nearPlane = std::max(1e-3f, distance * 0.01f);
    return glm::perspective(fovY, aspect, nearPlane, distance * 100.0f);
}

void Camera::orbit(float dxPixels, float dyPixels) {
    yaw -= dxPixels * kOrbitPerPixel;
    pitch = std::clamp(pitch + dyPixels * kOrbitPerPixel, -kMaxPitch, kMaxPitch);
}

void Camera::pan(float dxPixels, float dyPixels, float height) {
    // One pixel at the target's depth is this many metres.
    const float metresPerPixel = 2 * distance * std::tan(fovY / 2) / std::max(height, 1.0f);
    const glm::vec3 right = glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward());
    target += metresPerPixel * (-dxPixels * right + dyPixels * up);
}

void Camera::zoom(float wheelSteps) {
    distance = std::clamp(distance * std::pow(kZoomPerStep, wheelSteps), 1e-3f, 1e5f);
}

void Camera::frame(const Bounds& b, float aspect) {
    if (b.empty()) return;
    target = b.centre();
    const float r = std::max(b.radius(), 1e-2f);
    // A view narrower than tall sees less sideways: tan(fovX / 2) = aspect · tan(fovY / 2).
    const float halfX = std::atan(std::max(aspect, 1e-3f) * std::tan(fovY / 2));
    distance = r / std::sin(std::min(fovY / 2, halfX));
}

Ray Camera::ray(const glm::vec2& ndc, float aspect) const {
    const glm::mat4 inverse = glm::inverse(projection(aspect) * view());
    const glm::vec4 nearPoint = inverse * glm::vec4(ndc, -1, 1);
    const glm::vec4 farPoint = inverse * glm::vec4(ndc, 1, 1);
    const glm::vec3 a = glm::vec3(nearPoint) / nearPoint.w, b = glm::vec3(farPoint) / farPoint.w;
    return {eye(), glm::normalize(b - a)};
}

std::optional<std::int64_t> nearestToRay(const Ray& ray, const std::vector<glm::dvec3>& points,
                                         float maxAngle) {
    std::optional<std::int64_t> best;
    float bestAngle = maxAngle;
    for (std::size_t k = 0; k < points.size(); ++k) {
        const glm::vec3 d = glm::vec3(points[k]) - ray.origin;
        const float along = glm::dot(d, ray.direction);
        if (!(along > 0)) continue;  // behind the eye, or not finite
        const float off = glm::length(d - along * ray.direction);
        const float angle = std::atan2(off, along);
        if (angle < bestAngle) {
            bestAngle = angle;
            best = std::int64_t(k);
        }
    }
    return best;
}

std::optional<glm::vec3> intersectPlane(const Ray& ray, const glm::vec3& point,
                                        const glm::vec3& normal) {
    const float denom = glm::dot(ray.direction, normal);
    if (std::abs(denom) < 1e-6f) return std::nullopt;
    const float t = glm::dot(point - ray.origin, normal) / denom;
    if (!(t > 0)) return std::nullopt;
    return ray.origin + t * ray.direction;
}

}  // namespace cloth::render
