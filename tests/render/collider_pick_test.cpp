// The viewer's collider picking and drag plane (render/collider_pick.h), as pure geometry: the
// ray meets each shape where it is now (its motion and drag), the nearest wins, planes are not
// picked, and the drag target follows the cursor on the camera-facing plane.
#include "render/collider_pick.h"

#include <gtest/gtest.h>

#include <memory>

#include "model/collider_mesh.h"
#include "scene/collider_validate.h"

namespace cloth::render {
namespace {

Ray rayTo(const glm::vec3& from, const glm::vec3& to) {
    return {from, glm::normalize(to - from)};
}

Collider box(const glm::dvec3& centre, const glm::dvec3& half) {
    Box b;
    b.center = centre;
    b.halfExtents = half;
    return b;
}

TEST(ColliderPick, RayMeetsTheNearFaceOfABox) {
    const std::vector<Collider> cs = {box({0, 0, 0}, {0.5, 0.1, 0.3})};
    const auto hit = pickCollider(rayTo({0.2f, 5, 0.1f}, {0.2f, 0, 0.1f}), cs, 0, {});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->index, 0u);
    EXPECT_NEAR(hit->point.y, 0.1, 2e-4);
    EXPECT_NEAR(hit->point.x, 0.2, 1e-6);
    EXPECT_NEAR(hit->distance, 4.9, 2e-4);
    EXPECT_FALSE(pickCollider(rayTo({0.7f, 5, 0}, {0.7f, 0, 0}), cs, 0, {})) << "beside it";
    EXPECT_FALSE(pickCollider(rayTo({0, 5, 0}, {0, 10, 0}), cs, 0, {})) << "looking away";
}

TEST(ColliderPick, NearestOfSeveralWinsAndPlanesAreNotPicked) {
    Collider plane = Plane{glm::dvec3(0, -1, 0), glm::dvec3(0, 1, 0)};
    Collider capsule = Capsule{glm::dvec3(-1, 0.5, 0), glm::dvec3(1, 0.5, 0), 0.1};
    Collider sphere = Sphere{glm::dvec3(0, 0, 0), 0.2};
    const std::vector<Collider> cs = {plane, sphere, capsule};
    const auto hit = pickCollider(rayTo({0, 5, 0}, {0, 0, 0}), cs, 0, {});
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->index, 2u) << "the capsule above the sphere";
    EXPECT_NEAR(hit->point.y, 0.6, 2e-4);
    const auto side = pickCollider(rayTo({0, 5, 0.15f}, {0, -5, 0.15f}), cs, 0, {});
    ASSERT_TRUE(side);
    EXPECT_EQ(side->index, 1u) << "past the capsule's radius, the sphere";
    EXPECT_FALSE(pickCollider(rayTo({3, 5, 0}, {3, 0, 0}), cs, 0, {})) << "only the plane there";
}

// The shape is picked where it is drawn: moved by its drag (and motion) at the given time.
TEST(ColliderPick, PicksTheColliderWhereItsDragHasPutIt) {
    const std::vector<Collider> cs = {Sphere{glm::dvec3(0), 0.2}};
    const std::vector<ColliderDrag> drags = {{glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), 2.0}};
    // At t = 3 s the drag has moved it to (1, 0, 1).
    EXPECT_FALSE(pickCollider(rayTo({0, 5, 0}, {0, 0, 0}), cs, 3.0, drags));
    const auto hit = pickCollider(rayTo({1, 5, 1}, {1, 0, 1}), cs, 3.0, drags);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.y, 0.2, 2e-4);
}

// A mesh is marched through its grid: the hit is on the baked block's top within a cell.
TEST(ColliderPick, RayMeetsAMeshThroughItsGrid) {
    auto baked = std::make_shared<BakedMesh>();
    baked->mesh = boxMesh({glm::dvec3(0), glm::dvec3(0.3, 0.1, 0.2), glm::dmat3(1)});
    baked->grid = bakeSdf(baked->mesh, 0.02, 0.06);
    MeshCollider m;
    m.baked = baked;
    m.translation = {0, 0.5, 0};
    const std::vector<Collider> cs = {m};
    const auto hit = pickCollider(rayTo({0.1f, 4, 0.05f}, {0.1f, 0, 0.05f}), cs, 0, {});
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->point.y, 0.6, 0.02);
    EXPECT_FALSE(pickCollider(rayTo({0.5f, 4, 0}, {0.5f, 0, 0}), cs, 0, {}));
}

// The drag plane faces the camera through the picked point; moving the cursor's ray by d there
// moves the target offset by d.
TEST(ColliderDragPlane, TargetFollowsTheRayOnTheCameraFacingPlane) {
    const glm::dvec3 picked(0, 0.1, 0), normal(0, 0, -1), start(0.05, 0, 0);
    const auto same = dragTarget(rayTo({0, 0.1f, 3}, {0, 0.1f, 0}), picked, normal, start);
    ASSERT_TRUE(same);
    EXPECT_NEAR(glm::length(*same - start), 0, 1e-6);
    const auto moved = dragTarget(rayTo({0.3f, 0.4f, 3}, {0.3f, 0.4f, 0}), picked, normal, start);
    ASSERT_TRUE(moved);
    EXPECT_NEAR(moved->x, 0.35, 1e-6);
    EXPECT_NEAR(moved->y, 0.3, 1e-6);
    EXPECT_NEAR(moved->z, 0, 1e-6);
    EXPECT_FALSE(dragTarget(rayTo({0, 0, 3}, {0, 0, 4}), picked, normal, start)) << "behind";
}

}  // namespace
}  // namespace cloth::render
