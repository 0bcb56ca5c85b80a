// The viewer's collider drag through its session (in-process, no window): the collider heads for
// the cursor's offset and reaches it at the end of the frame, no faster than the tunnelling limit
// of docs/colliders.md §7; release leaves it where it is; drags follow switched-off colliders,
// survive live edits and solver rebuilds, and reset clears them; the GPU drags too.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "model/collider_limits.h"
#include "model/collider_speed.h"
#include "model/errors.h"
#include "render/image_checks.h"
#include "scene/scene_loader.h"
#include "viewer/viewer_session.h"

namespace cloth {
namespace {

using app::ViewerParams;
using app::ViewerSession;

const std::string kScenes = CLOTH_SOURCE_DIR "/scenes/";

// drape's cloth, ground and sphere, with a box below the ground out of the way (collider 2).
Scene dragScene() {
    return loadScene(kScenes + "drape.json",
                     {"cloth.resolution=[8,6]", "integrator.substeps=20",
                      R"(colliders=[{"type":"plane","point":[0,0,0],"normal":[0,1,0]},)"
                      R"({"type":"sphere","center":[0,0.5,0],"radius":0.3},)"
                      R"({"type":"box","center":[0,-2,0],"half_extents":[0.2,0.05,0.2],)"
                      R"("thickness":0.01}])"});
}

Scene smallDrape() {
    return loadScene(kScenes + "drape.json", {"cloth.resolution=[8,6]", "integrator.substeps=20"});
}

TEST(ViewerDrag, ColliderReachesTheTargetAtTheEndOfTheFrame) {
    ViewerSession s(dragScene(), {});
    const glm::dvec3 target(0.004, 0.002, 0);  // slower than the limit over one frame
    s.dragCollider(2, target);
    ASSERT_NE(s.colliderDrag(2), nullptr);
    const double frame = 20 * s.params().scene.integrator.dt;
    EXPECT_NEAR(glm::length(s.colliderDrag(2)->velocity - target / frame), 0, 1e-12);
    s.advance();
    EXPECT_NEAR(glm::length(s.colliderOffset(2) - target), 0, 1e-12);
    s.dragCollider(2, target);  // the cursor stayed: it stops there
    EXPECT_EQ(glm::length(s.colliderDrag(2)->velocity), 0);
    s.releaseCollider(2);
    s.advance();
    s.advance();
    EXPECT_NEAR(glm::length(s.colliderOffset(2) - target), 0, 1e-12) << "offsets persist";
    const std::vector<ColliderDrag> drawn = s.effectiveDrags();
    ASSERT_EQ(drawn.size(), 3u);
    EXPECT_NEAR(glm::length(drawn[2].at(s.solver().time()) - target), 0, 1e-12);
}

// A far target: the drag speed is clamped so that one step moves the box at most its half
// thickness plus its thickness (0.05 + 0.01 m); it catches up over later frames.
TEST(ViewerDrag, DragSpeedIsClampedToTheTunnellingLimit) {
    ViewerSession s(dragScene(), {});
    const Collider& box = s.params().scene.colliders[2];
    const double dt = s.params().scene.integrator.dt;
    s.dragCollider(2, glm::dvec3(100, 0, 0));
    EXPECT_NEAR(glm::length(s.colliderDrag(2)->velocity) * dt, 0.06, 1e-12);
    EXPECT_NEAR(glm::length(s.colliderDrag(2)->velocity) * dt, maxColliderStepTravel(box), 1e-12);
    s.advance();
    EXPECT_NEAR(s.colliderOffset(2).x, 20 * 0.06, 1e-9);
    // The helper alone: a slow velocity is kept, a fast one keeps its direction.
    const glm::dvec3 slow(1, 2, 0), fast(0, 3e3, 4e3);
    EXPECT_EQ(app::clampDragVelocity(slow, box, dt), slow);
    const glm::dvec3 v = app::clampDragVelocity(fast, box, dt);
    EXPECT_NEAR(glm::length(v) * dt, 0.06, 1e-12);
    EXPECT_NEAR(glm::dot(glm::normalize(v), glm::normalize(fast)), 1, 1e-12);
    // A box that moves 0.01 m per step by itself (a linear motion) leaves the drag the
    // rest of the limit: together they still move at most 0.06 m in one step.
    Collider moving = box;
    moving.motion = ColliderMotion{};
    moving.motion->velocity = glm::dvec3(0, 0, 0.01 / dt);
    const glm::dvec3 w = app::clampDragVelocity(fast, moving, dt);
    EXPECT_NEAR((glm::length(w) + maxMotionSpeed(moving)) * dt, 0.06, 1e-12);
}

TEST(ViewerDrag, DragsFollowSwitchesLiveEditsAndRebuildsAndResetClearsThem) {
    ViewerSession s(dragScene(), {});
    s.dragCollider(2, glm::dvec3(0, 0.01, 0));
    s.advance();
    ViewerParams p = s.params();
    p.scene.colliders[2].friction = 0.5;  // live
    s.applyParameters(p);
    EXPECT_NEAR(s.colliderOffset(2).y, 0.01, 1e-12);
    p.colliderOn[1] = false;  // the sphere off: a new solver, the box is now its collider 1
    s.applyParameters(p);
    EXPECT_EQ(s.effectiveIndex(2), 1);
    EXPECT_EQ(s.paramsIndex(1), 2u);
    EXPECT_NEAR(s.colliderOffset(2).y, 0.01, 1e-12);
    s.dragCollider(2, glm::dvec3(0, 0.012, 0));
    s.advance();
    EXPECT_NEAR(s.colliderOffset(2).y, 0.012, 1e-12);
    EXPECT_EQ(s.effectiveDrags().size(), 2u);
    EXPECT_THROW(s.dragCollider(1, glm::dvec3(0)), std::invalid_argument) << "switched off";
    s.reset();
    EXPECT_EQ(s.colliderDrag(2), nullptr);
    EXPECT_EQ(s.colliderOffset(2), glm::dvec3(0));
}

// The GPU backend drags too (docs/colliders.md §9): the drape's plain sphere, dragged on the
// GPU, becomes a moving collider (the kernels compiled again, the state kept) and reaches the
// cursor's offset at the end of the frame with the cloth kept outside it; a switch to the CPU
// and back while it is dragged carries the drag and the time.
TEST(ViewerDrag, TheGpuBackendDragsAndSwitchesWhileDragging) {
    ViewerSession s(smallDrape(), {});
    try {
        s.setBackend({Backend::Gpu, Precision::Float, 0});
    } catch (const GpuUnavailable& e) {
        if (test::gpuRequiredByEnvironment()) FAIL() << e.what();
        GTEST_SKIP() << "no GPU: " << e.what();
    }
    for (int f = 0; f < 5; ++f) s.advance();
    const glm::dvec3 target(0.004, 0.002, 0);
    s.dragCollider(1, target);
    ASSERT_NE(s.colliderDrag(1), nullptr);
    s.advance();
    EXPECT_NEAR(glm::length(s.colliderOffset(1) - target), 0, 1e-12);
    const Sphere& sphere = *s.params().scene.colliders[1].as<Sphere>();
    double nearest = 1e300;
    for (const glm::dvec3& p : s.solver().read().positions)
        nearest = std::min(nearest, glm::length(p - (sphere.center + target)));
    EXPECT_GT(nearest, sphere.radius - 1e-5) << "a vertex inside the dragged sphere";
    s.dragCollider(1, glm::dvec3(0.01, 0.002, 0));
    const double t = s.solver().time();
    s.setBackend({Backend::Cpu, Precision::Float, 1});
    EXPECT_EQ(s.solver().time(), t);
    s.setBackend({Backend::Gpu, Precision::Float, 0});
    EXPECT_EQ(s.backend().backend, Backend::Gpu);
    EXPECT_EQ(s.solver().time(), t);
    s.advance();
    EXPECT_NEAR(glm::length(s.colliderOffset(1) - glm::dvec3(0.01, 0.002, 0)), 0, 1e-12);
}

}  // namespace
}  // namespace cloth
