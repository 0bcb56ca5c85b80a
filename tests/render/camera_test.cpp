// The orbit camera and the viewer's picking maths.
#include "render/camera.h"

#include <gtest/gtest.h>

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
    c.frame(b);
    EXPECT_NEAR(glm::length(c.target - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
    EXPECT_GT(c.distance, b.radius());
    c.orbit(0, 1e6f);
    EXPECT_LT(c.pitch, 1.5708f);
    const float d = c.distance;
    c.zoom(1);
    EXPECT_LT(c.distance, d);
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
