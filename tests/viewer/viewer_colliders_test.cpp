// The viewer's collider switches with follow pins, and its parameter edits against the tunnelling
// limit (in-process, no window): switching off a collider before the followed one keeps the pins
// following it (their indices renumbered); switching off the followed one leaves them still, where
// they are; a Δt or a motion that would let a collider outrun docs/colliders.md §7's limit is
// refused with the loader's message, changing nothing.
#include <gtest/gtest.h>

#include <utility>

#include "model/collider_motion.h"
#include "model/errors.h"
#include "scene/scene_loader.h"
#include "viewer/viewer_session.h"

namespace cloth {
namespace {

using app::ViewerParams;
using app::ViewerSession;

// The windsock with its colliders swapped: the ground plane is colliders[0], the swaying pole
// colliders[1], which the 16 pins of the flag's edge follow.
Scene windsockPoleSecond() {
    Scene s = loadScene(CLOTH_SOURCE_DIR "/scenes/windsock.json");
    std::swap(s.colliders[0], s.colliders[1]);
    for (Pin& p : s.pins) p.follow = 1;
    return s;
}

// Where the follow pins are now, against where the pole's pose puts them; the largest distance.
double pinsOffThePole(const ViewerSession& s) {
    const Scene& scene = s.params().scene;
    const Motion m = scene.colliders[1].motion->motion();
    const Grid g = scene.grid();
    const SimState st = s.solver().read();
    double worst = 0;
    for (const Pin& p : scene.pins) {
        const glm::dvec3 want = poseAt(m, s.solver().time()).apply(g.restPosition(p.i, p.j));
        worst = std::max(worst, glm::length(st.positions[std::size_t(g.index(p.i, p.j))] - want));
    }
    return worst;
}

// Law (docs/colliders.md §5): a follow pin goes with its collider's pose. With the ground (before
// the pole) switched off the solver's pole is its colliders[0]: the pins still follow it.
TEST(ViewerColliders, SwitchingOffAnotherColliderKeepsThePinsFollowing) {
    ViewerSession s(windsockPoleSecond(), {});
    ViewerParams p = s.params();
    p.colliderOn[0] = false;
    s.applyParameters(p);
    ASSERT_EQ(s.solver().features().planes, 0);
    for (int f = 0; f < 10; ++f) s.advance();
    ASSERT_FALSE(s.unstable()) << s.instability();
    EXPECT_GT(s.solver().time(), 0.15);
    EXPECT_LT(pinsOffThePole(s), 1e-12) << "the pins stopped following the pole";
}

// A pin whose collider is switched off becomes a still pin, held where it is: the flag's edge
// stops where the pole left it (the pole itself no longer moves anything), and does not fall.
TEST(ViewerColliders, SwitchingOffTheFollowedColliderLeavesThePinsStill) {
    ViewerSession s(windsockPoleSecond(), {});
    for (int f = 0; f < 5; ++f) s.advance();
    ViewerParams p = s.params();
    p.colliderOn[1] = false;
    s.applyParameters(p);
    const Grid g = s.params().scene.grid();
    const SimState before = s.solver().read();
    for (int f = 0; f < 10; ++f) s.advance();
    ASSERT_FALSE(s.unstable()) << s.instability();
    const SimState after = s.solver().read();
    for (const Pin& pin : s.params().scene.pins) {
        const std::size_t k = std::size_t(g.index(pin.i, pin.j));
        EXPECT_EQ(after.positions[k], before.positions[k]) << pin.i << ", " << pin.j;
        EXPECT_EQ(after.velocities[k], glm::dvec3(0));
    }
    // On again: they follow the pole's pose once more.
    p = s.params();
    p.colliderOn[1] = true;
    s.applyParameters(p);
    s.advance();
    EXPECT_LT(pinsOffThePole(s), 1e-12);
}

// docs/colliders.md §7's rule holds for the viewer's edits as for the loader: the pole sways at
// up to 0.47 m/s against r + h = 3 cm per step, so Δt = 0.07 s, or a 100 Hz swing (94 m/s) at Δt =
// 0.4 ms, is refused, naming colliders[n].motion, and nothing changes; with the pole switched off
// both pass.
TEST(ViewerColliders, EditsThatWouldOutrunTheTunnellingLimitAreRefused) {
    ViewerSession s(windsockPoleSecond(), {});
    const double dt = s.params().scene.integrator.dt;
    ViewerParams p = s.params();
    p.scene.integrator.dt = 0.07;
    try {
        s.applyParameters(p);
        ADD_FAILURE() << "Δt = 0.07 s was taken";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "colliders[1].motion") << e.what();
    }
    EXPECT_EQ(s.params().scene.integrator.dt, dt);
    p = s.params();
    p.scene.colliders[1].motion->frequency = 100;
    EXPECT_THROW(s.applyParameters(p), InputError);
    EXPECT_EQ(s.params().scene.colliders[1].motion->frequency, 0.5);
    p.colliderOn[1] = false;
    EXPECT_NO_THROW(s.applyParameters(p));
    p.scene.integrator.dt = 0.07;
    EXPECT_NO_THROW(s.applyParameters(p));
}

}  // namespace
}  // namespace cloth
