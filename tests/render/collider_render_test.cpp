// The renderer draws every collider type where it projects: a box, a capsule and a mesh (a
// torus) from tests/data/colliders_scene.json, in process, read back from the offscreen target;
// moving colliders at the solver's time, and a drag's offset where the viewer put it.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "cpu/cpu_backend.h"
#include "gpu/gpu_test_support.h"
#include "render/image.h"
#include "render/image_checks.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"

namespace cloth::render {
namespace {

const std::string kScene = CLOTH_SOURCE_DIR "/tests/data/colliders_scene.json";
constexpr int kWidth = 480, kHeight = 360;

class ColliderRender : public test::GpuTest {
protected:
    // The target needs the GL context, which GpuTest::SetUp makes (or skips the test without):
    // a member initialiser would run first, without a context when the test runs alone.
    void SetUp() override {
        test::GpuTest::SetUp();
        if (IsSkipped() || HasFatalFailure()) return;
        target_.emplace(kWidth, kHeight);
    }

    // The picture with the cloth moved far away (the colliders alone), from a fixed camera.
    Image draw(Renderer& r, const Solver& solver) {
        r.updateCloth(solver);
        target_->bind();
        RenderOptions o;
        o.wind = false;
        r.draw(camera_, o, kWidth, kHeight);
        return target_->read();
    }
    // The pixel where world point p projects (top row first).
    glm::ivec2 pixelOf(const glm::dvec3& p) const {
        const glm::vec4 c = camera_.projection(float(kWidth) / kHeight) * camera_.view() *
                            glm::vec4(glm::vec3(p), 1);
        const glm::vec2 ndc = glm::vec2(c) / c.w;
        return {int((ndc.x + 1) * 0.5f * kWidth), int((1 - ndc.y) * 0.5f * kHeight)};
    }
    // Whether most of the 5×5 pixels around p's projection are the colliders' teal.
    bool tealAt(const Image& im, const glm::dvec3& p) const {
        const glm::ivec2 q = pixelOf(p);
        int teal = 0;
        for (int y = q.y - 2; y <= q.y + 2; ++y)
            for (int x = q.x - 2; x <= q.x + 2; ++x) {
                if (x < 0 || y < 0 || x >= kWidth || y >= kHeight) continue;
                const std::uint8_t* c = &im.rgba[(std::size_t(y) * kWidth + x) * 4];
                teal += test::sphereTeal(c[0], c[1], c[2]);
            }
        return teal > 12;
    }

    Camera camera_ = [] {
        Camera c;
        c.target = {0, 0.15f, 0};
        c.yaw = 0;
        c.pitch = 0.5f;
        c.distance = 2.6f;
        return c;
    }();
    std::optional<OffscreenTarget> target_;
};

// The cloth far above the view: only the colliders (and the ground) are in the picture.
Scene collidersOnly() {
    return loadScene(kScene, {"cloth.origin=[-1, 30, -0.5]"});
}

TEST_F(ColliderRender, BoxCapsuleAndMeshAppearWhereTheyProject) {
    const Scene s = collidersOnly();
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    Renderer r;
    r.setScene(s);
    const Image im = draw(r, *solver);
    // The box's top centre, the capsule's top line, the torus's ring (30° about x, at phase 0).
    EXPECT_TRUE(tealAt(im, {-0.6, 0.4, 0})) << "box";
    EXPECT_TRUE(tealAt(im, {0, 0.27, 0.2})) << "capsule";
    EXPECT_TRUE(tealAt(im, {0, 0.27, -0.2})) << "capsule";
    EXPECT_TRUE(tealAt(im, {0.6 + 0.16, 0.1, 0})) << "torus, right of its hole";
    EXPECT_TRUE(tealAt(im, {0.6 - 0.16, 0.1, 0})) << "torus, left of its hole";
    EXPECT_FALSE(tealAt(im, {0.6, 0.1, 0})) << "the torus's hole shows the ground";
    EXPECT_FALSE(tealAt(im, {-0.3, 0.05, 0.45})) << "ground between box and capsule";
    // The frame contains all of them.
    const Bounds b = r.sceneBounds();
    EXPECT_LT(b.lo.x, -0.8f);
    EXPECT_GT(b.hi.x, 0.75f);
}

// The torus oscillates along z with 0.1 m at 0.5 Hz: at t = 0.5 s it is 0.1 m along +z, and it is
// drawn there, at the solver's time. A drag's offset moves the box.
TEST_F(ColliderRender, MovingAndDraggedCollidersAreDrawnWhereTheSolverHasThem) {
    const Scene s = collidersOnly();
    auto solver = makeCpuSolver(s, {Precision::Double, 1});
    solver->step(1000);  // 0.5 s
    ASSERT_NEAR(solver->time(), 0.5, 1e-12);
    Renderer r;
    r.setScene(s);
    r.setColliderDrags({{}, {glm::dvec3(0, 0, 0.6), glm::dvec3(0), 0}});  // the box, 0.6 m nearer
    const Image im = draw(r, *solver);
    EXPECT_TRUE(tealAt(im, {0.6 + 0.16, 0.1 + 0.05, 0.1})) << "torus moved along z";
    EXPECT_TRUE(tealAt(im, {-0.6, 0.4, 0.6})) << "box where the drag put it";
    EXPECT_FALSE(tealAt(im, {-0.6, 0.4, 0})) << "nothing where the box was";
}

}  // namespace
}  // namespace cloth::render
