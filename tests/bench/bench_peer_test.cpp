// bench speed --peer: the explosion check and the stiffness mapping in-process; with Bullet
// compiled in, a 16² btSoftBody patch that stays finite and sags like ours, and peer rows in the
// CSV; without it, the clear refusal (exit 2 naming --peer).
#include "bench/bench_peer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "cpu/cpu_backend.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/process.h"

namespace cloth {
namespace {

using test::runProcess;

TEST(BenchPeer, ExplosionCheck) {
    const std::vector<glm::dvec3> start{{0, 0, 0}, {1, 0, 0}};
    EXPECT_FALSE(app::peerExplosion(start, {{0, -2, 0}, {1, -3, 0}}, 1.0).has_value());
    EXPECT_TRUE(app::peerExplosion(start, {{0, -6, 0}, {1, 0, 0}}, 1.0).has_value());
    EXPECT_TRUE(app::peerExplosion(start, {{0, NAN, 0}, {1, 0, 0}}, 1.0).has_value());
    EXPECT_TRUE(app::peerExplosion(start, {{0, 0, 0}}, 1.0).has_value());
    EXPECT_TRUE(app::peerFrozen(start, start));
    EXPECT_FALSE(app::peerFrozen(start, {{0, -1e-9, 0}, {1, 0, 0}}));
}

// One iteration of kLST removes the fraction of a link's error that an explicit spring's
// impulse K·C·dt would: 2K dt²/m while that is small, never 1 or more.
TEST(BenchPeer, LinkStiffnessMapping) {
    EXPECT_NEAR(app::bulletLinkStiffness(400, 0.006, 2e-5), 2 * 400 * 4e-10 / 0.006, 1e-8);
    EXPECT_LT(app::bulletLinkStiffness(1e9, 1e-3, 1), 1.0);
    EXPECT_GT(app::bulletLinkStiffness(1e9, 1e-3, 1), 0.99);
    EXPECT_DOUBLE_EQ(app::bulletDamping(0.12, 0.006, 2e-5), 0.12 * 2e-5 / 0.006);
}

TEST(BenchPeer, UnknownPeerIsRefusedNamingTheFlag) {
    EXPECT_TRUE(app::peerUnavailable("havok").has_value());
    const auto r = runProcess({CLOTH_EXE, "bench", "speed", "--peer", "havok"}, 60);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--peer"), std::string::npos) << r.err;
}

#ifdef CLOTH_HAVE_BULLET

// The speed benchmark's default scene: the seed's per-vertex hanging cloth.
Scene hanging(int n) {
    return loadScene(CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json",
                     {"cloth.resolution=[" + std::to_string(n) + "," + std::to_string(n) + "]"});
}

// 0.1 s at the scene's dt: finite, the pinned corners where they were, the free corners fallen,
// and by as much as ours: the stiffness and damping mapping gives the same motion.
TEST(BenchPeer, BulletPatchStaysFiniteAndSags) {
    const Scene s = hanging(16);
    const long steps = std::lround(0.1 / s.integrator.dt);
    auto peer = app::makePeerCloth("bullet", s);
    const auto start = peer->positions();
    peer->step(steps);
    const auto end = peer->positions();
    EXPECT_FALSE(app::peerExplosion(start, end, s.grid().extent()).has_value());
    const Grid g = s.grid();
    for (int i : {0, 15}) EXPECT_EQ(end[g.index(i, 0)], start[g.index(i, 0)]);  // pinned
    auto ours = makeCpuSolver(s, {Precision::Double, 1});
    ASSERT_FALSE(ours->step(steps).unstable);
    const SimState o = ours->read();
    for (int i : {0, 15}) {
        const std::size_t k = g.index(i, 15);  // a free corner
        const double drop = start[k].y - end[k].y, ourDrop = start[k].y - o.positions[k].y;
        EXPECT_GT(drop, 0.02) << i;
        EXPECT_NEAR(drop, ourDrop, 0.02 * ourDrop) << i;  // 0.028 m both (0.04% apart)
    }
    EXPECT_NE(peer->describe().find("iterations"), std::string::npos);

    // At 50 times our step (past our explicit Euler's bound of about 3e-5 s) Bullet's projection
    // still holds, and with kLST and kDP mapped at that step it still falls as ours (0.0282 m).
    Scene coarse = s;
    coarse.integrator.dt *= 50;
    auto big = app::makePeerCloth("bullet", coarse);
    big->step(steps / 50);
    const auto bigEnd = big->positions();
    EXPECT_FALSE(app::peerExplosion(start, bigEnd, s.grid().extent()).has_value());
    for (int i : {0, 15}) {
        const std::size_t k = g.index(i, 15);
        const double ourDrop = start[k].y - o.positions[k].y;
        EXPECT_NEAR(start[k].y - bigEnd[k].y, ourDrop, 0.05 * ourDrop) << i;
    }
}

TEST(BenchPeer, BenchSpeedWritesPeerRows) {
    const auto d = test::freshTempDir("peer_test", "rows");
    const auto r = runProcess({CLOTH_EXE, "bench", "speed", "--peer", "bullet", "--sizes", "16",
                               "--backend", "cpu", "--quick", "--out", d.string(), "--label", "p"},
                              120);
    ASSERT_EQ(r.exitCode, 0) << test::describe(r);
    std::ifstream in(d / "speed_p.json");
    const auto j = nlohmann::json::parse(in);
    EXPECT_NE(j["peer"].get<std::string>().find("Bullet"), std::string::npos);
    int peers = 0, ours = 0;
    for (const auto& row : j["rows"]) {
        if (row["target"] == "peer_bullet") {
            ++peers;
            EXPECT_EQ(row["status"], "ok");
            EXPECT_GT(row["vertex_steps_per_s"].get<double>(), 0);
            EXPECT_GT(row["bytes_per_vertex"].get<double>(), 100);  // a node alone is more
        } else if (row["target"] == "cpu_double") {
            ++ours;
            EXPECT_GT(row["peer_ratio"].get<double>(), 0);
        }
    }
    EXPECT_EQ(peers, 1);
    EXPECT_EQ(ours, 1);
}

#else

TEST(BenchPeer, BuildWithoutBulletSaysSo) {
    ASSERT_TRUE(app::peerUnavailable("bullet").has_value());
    const auto r = runProcess({CLOTH_EXE, "bench", "speed", "--peer", "bullet"}, 60);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find("--peer"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("without Bullet"), std::string::npos) << r.err;
}

#endif

}  // namespace
}  // namespace cloth
