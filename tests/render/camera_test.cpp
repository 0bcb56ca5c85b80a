// The orbit camera and the viewer's picking maths.
#include "render/camera.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cloth::render {
namespace {

TEST(Camera, CentreRayLooksAtTheTarget) {
    Camera c;
    c.target = {0.3f, 0.5f, -0.2f};
    c.distance = 4;
    const Ray r = c.ray({0, 0}, 1.5f);
    EXPECT_NEAR(glm::length(r.origin - c.eye()), 0.0f, 1e-5f);
    const glm::vec3 toTarget = glm::normalize(c.target - c.eye());
    EXPECT_NEAR(glm::dot(r.direction, toTarget), 1.0f, 1e-5f);
}

TEST(Camera, FrameFitsTheBoundsAndOrbitKeepsThePitchBelowVertical) {
    Camera c;
    Bounds b;
    b.add({-1, 0, -1});
    b.add({1, 2, 1});
    c.frame(b, 1.5f);
    EXPECT_NEAR(glm::length(c.target - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_GT(c.distance, b.radius());
    c.orbit(0, 1e6f);
    EXPECT_LT(c.pitch, 1.5708f);
    const float d = c.distance;
    c.zoom(1);
    EXPECT_LT(c.distance, d);
}

// Law: a framed bounding sphere of radius r seen from distance d subtends asin(r / d) each side;
// it fits a view when that is at most the narrower half field of view. A wide view is limited by
// fovY, a tall one by fovX, tan(fovX / 2) = aspect · tan(fovY / 2): the sphere then touches the
// view's sides, and its rays through the view's edges (ndc ±1) just graze it.
TEST(Camera, FrameFitsTheBoundingSphereInTheNarrowerFieldOfView) {
    Bounds b;
    b.add({-1, 0, -1});
    b.add({1, 2, 1});
    for (const float aspect : {2.0f, 1.0f, 0.5f, 0.25f}) {
        Camera c;
        c.frame(b, aspect);
        const float halfY = c.fovY / 2, halfX = std::atan(aspect * std::tan(halfY));
        const float seen = std::asin(b.radius() / c.distance);
        EXPECT_NEAR(seen, std::min(halfX, halfY), 1e-5f) << "aspect " << aspect;
        // The ray through the middle of the narrower edge is tangent to the sphere.
        const Ray edge = c.ray(aspect < 1 ? glm::vec2(1, 0) : glm::vec2(0, 1), aspect);
        const glm::vec3 toCentre = b.centre() - edge.origin;
        const float miss =
            glm::length(toCentre - glm::dot(toCentre, edge.direction) * edge.direction);
        EXPECT_NEAR(miss, b.radius(), 1e-3f * b.radius()) << "aspect " << aspect;
    }
}

TEST(Picking, NearestVertexToTheRayWithinTheAngle) {
    const Ray ray{{0, 0, 5}, {0, 0, -1}};
    const std::vector<glm::dvec3> points = {{0.5, 0, 0}, {0.02, 0.01, 0}, {0, 0, 10}, {0, 0.3, 1}};
    const auto k = nearestToRay(ray, points);
    ASSERT_TRUE(k.has_value());
    EXPECT_EQ(*k, 1);  // {0, 0, 10} is behind the eye
    EXPECT_FALSE(nearestToRay(ray, {{1, 1, 0}}).has_value());
}

TEST(Picking, DragPlaneThroughTheGrabbedPoint) {
    const Ray ray{{0, 0, 5}, glm::normalize(glm::vec3(0.1f, 0, -1))};
    const auto hit = intersectPlane(ray, {0, 0, 1}, {0, 0, 1});
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->z, 1.0f, 1e-5f);
    EXPECT_NEAR(hit->x, 0.4f, 1e-5f);
    EXPECT_FALSE(intersectPlane(ray, {0, 0, 6}, {0, 0, 1}).has_value());  // behind
}

}  // namespace
}  // namespace cloth::render
