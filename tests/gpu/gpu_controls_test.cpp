// The interactive controls of the Solver interface on the GPU (the viewer's write, pins, grab
// and parameter changes): each does on the GPU what it does on the CPU float backend, and a
// parameter change reaches the kernels without recompiling them.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cpu/cpu_backend.h"
#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

// Float against float, smooth physics (as gpu_parity_test.cpp): rounding order only.
constexpr double kFloatTolerance = 1e-6;
// Where the cloth rests on a sphere, last-bit differences decide "inside or not" (docs/gpu.md).
constexpr double kContactTolerance = 1e-4;

const Json kFarSphere = {{"type", "sphere"}, {"center", {0, -5, 0}}, {"radius", 0.5}};
const Json kNearSphere = {{"type", "sphere"}, {"center", {0.05, 0.9, 0.0}}, {"radius", 0.3}};
const Json kPlane = {{"type", "plane"}, {"point", {0, -4, 0}}, {"normal", {0, 1, 0}}};

// gpu_parity_test.cpp's tilted cloth (Δt inside explicit Euler's bound), with wind and one
// sphere: every runtime parameter of the kernels is in use.
Json baseJson(const Json& sphere = kFarSphere) {
    Json j = Json::parse(R"({
      "name": "gpu-controls",
      "cloth": { "resolution": [19, 13], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]],
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "wind": { "direction": [1, 0.2, 0.6], "strength": 2.0 }
    })");
    j["colliders"] = Json::array({sphere});
    return j;
}

Scene sceneOf(const Json& j, const char* what) {
    return parseScene(j.dump(), std::string("gpu controls: ") + what);
}

struct Pair {  // the same run on both float backends
    std::unique_ptr<Solver> gpu, cpu;
    explicit Pair(const Scene& s)
        : gpu(makeGpuSolver(s)), cpu(makeCpuSolver(s, {Precision::Float, 1})) {}
    template <typename F>
    void both(F f) {
        f(*gpu);
        f(*cpu);
    }
    void step(long n) {
        both([n](Solver& s) {
            const StepResult r = s.step(n);
            EXPECT_FALSE(r.unstable) << s.name() << ": " << r.reason;
        });
    }
    double difference(double extent) const {
        return maxDifferenceOverExtent(gpu->read(), cpu->read(), extent);
    }
};

class GpuControls : public GpuTest {};

// A state written into a solver continues there as on the backend it came from: CPU → GPU and
// GPU → CPU.
TEST_F(GpuControls, WrittenStateContinuesAsOnTheCpu) {
    const Scene s = sceneOf(baseJson(), "write");
    const double extent = s.grid().extent();
    auto donor = makeCpuSolver(s, {Precision::Float, 1});
    donor->step(300);
    auto gpu = makeGpuSolver(s);
    gpu->write(donor->read());
    const double written = maxDifferenceOverExtent(gpu->read(), donor->read(), extent);
    EXPECT_EQ(written, 0.0) << "float state → double → float is exact";
    donor->step(200);
    gpu->step(200);
    const double cpuToGpu = maxDifferenceOverExtent(gpu->read(), donor->read(), extent);
    auto cpu = makeCpuSolver(s, {Precision::Float, 1});
    cpu->write(gpu->read());
    gpu->step(200);
    cpu->step(200);
    const double gpuToCpu = maxDifferenceOverExtent(gpu->read(), cpu->read(), extent);
    std::printf("write: cpu→gpu +200 steps %.3g, gpu→cpu +200 steps %.3g (/ extent)\n", cpuToGpu,
                gpuToCpu);
    EXPECT_LT(cpuToGpu, kFloatTolerance);
    EXPECT_LT(gpuToCpu, kFloatTolerance);
    SimState wrong = donor->read();
    wrong.nu += 1;
    EXPECT_THROW(gpu->write(wrong), std::invalid_argument);
}

// The viewer's reset after a blow-up: writing a sane state lets the kernels run again.
TEST_F(GpuControls, WriteClearsAnEarlierInstability) {
    Json j = baseJson();
    j["integrator"]["dt"] = 0.02;  // far beyond μ/λ_max
    const Scene s = sceneOf(j, "unstable");
    auto gpu = makeGpuSolver(s);
    const SimState start = gpu->read();
    const StepResult bad = gpu->step(2000);
    ASSERT_TRUE(bad.unstable);
    gpu->write(start);
    gpu->resetStepCount();
    const long good = bad.firstBadStep - 1;
    const StepResult again = gpu->step(good);
    EXPECT_FALSE(again.unstable) << again.reason;
    EXPECT_EQ(again.stepsTaken, good);
    auto fresh = makeGpuSolver(s);
    fresh->step(good);
    EXPECT_EQ(gpu->read().positions, fresh->read().positions);  // the same run again
    const StepResult last = gpu->step(10);
    EXPECT_TRUE(last.unstable);
    EXPECT_EQ(last.firstBadStep, bad.firstBadStep);
}

// DESIGN.md §2: a pinned vertex is held at its pinned position with zero velocity, bit for bit;
// released, it falls. Pins beyond the scene's own (and beyond the table's first allocation)
// and the release of a scene pin work alike on both backends.
TEST_F(GpuControls, SetPinnedHoldsTheVertexExactlyAndReleaseLetsItFall) {
    const Scene s = sceneOf(baseJson(), "pins");
    const Grid g = s.grid();
    const double extent = g.extent();
    Pair run(s);
    run.step(200);
    std::vector<std::pair<int, int>> pinned = {{9, 6}};
    for (int i = 0; i < g.nu; ++i) pinned.emplace_back(i, 3);  // 20 new pins: the table grows
    const SimState before = run.gpu->read();
    run.both([&](Solver& solver) {
        for (auto [i, j] : pinned) solver.setPinned(i, j, true);
        solver.setPinned(0, g.nv - 1, false);  // a scene pin, released
    });
    for (int chunk = 0; chunk < 4; ++chunk) {
        run.step(100);
        const SimState now = run.gpu->read();
        for (auto [i, j] : pinned) {
            const std::int64_t k = g.index(i, j);
            EXPECT_EQ(now.positions[k], before.positions[k]) << i << ", " << j;
            EXPECT_EQ(now.velocities[k], glm::dvec3(0)) << i << ", " << j;
        }
        EXPECT_LT(run.difference(extent), kFloatTolerance) << "after " << 100 * (chunk + 1);
    }
    const std::int64_t released = g.index(0, g.nv - 1), centre = g.index(9, 6);
    EXPECT_LT(run.gpu->read().positions[released].y, before.positions[released].y - 0.01);
    run.both([&](Solver& solver) { solver.setPinned(9, 6, false); });
    run.step(300);
    const double afterRelease = run.difference(extent);
    std::printf("setPinned: 21 pins + 1 release, then 1 more release: gpu vs cpu %.3g\n",
                afterRelease);
    EXPECT_LT(run.gpu->read().positions[centre].y, before.positions[centre].y - 0.01)
        << "released, it should fall";
    EXPECT_LT(afterRelease, kFloatTolerance);
    EXPECT_THROW(run.gpu->setPinned(g.nu, 0, true), std::invalid_argument);
    EXPECT_THROW(run.gpu->setPinned(0, -1, true), std::invalid_argument);
}

// A scene without pins compiles the same kernels: pinning at run time needs no rebuild.
TEST_F(GpuControls, PinningWorksInASceneThatDeclaresNone) {
    Json j = baseJson();
    j.erase("pins");
    const Scene s = sceneOf(j, "no pins");
    Pair run(s);
    run.both([](Solver& solver) { solver.setPinned(9, 12, true); });
    const glm::dvec3 at = run.gpu->read().positions[s.grid().index(9, 12)];
    run.step(400);
    EXPECT_EQ(run.gpu->read().positions[s.grid().index(9, 12)], at);
    EXPECT_LT(run.difference(s.grid().extent()), kFloatTolerance);
}

// F = K (target − x) on one vertex, in the forces pass: it pulls the vertex toward the target
// (against the falling cloth it hangs in) as on the CPU; removed, nothing of it remains.
TEST_F(GpuControls, GrabPullsTheVertexTowardTheTargetAsOnTheCpu) {
    const Scene s = sceneOf(baseJson(), "grab");
    const Grid g = s.grid();
    const double extent = g.extent();
    Pair run(s);
    auto ungrabbed = makeGpuSolver(s);
    run.step(100);
    ungrabbed->step(100);
    const std::int64_t k = g.index(9, 4);
    const glm::dvec3 x0 = run.gpu->read().positions[k];
    const glm::dvec3 target = x0 + glm::dvec3(0.1, 0.5, -0.2);
    run.both([&](Solver& solver) { solver.setGrab(Grab{k, target, 400.0}); });
    run.step(400);
    ungrabbed->step(400);
    const double pulled = glm::length(target - run.gpu->read().positions[k]);
    const double free = glm::length(target - ungrabbed->read().positions[k]);
    const double grabbed = run.difference(extent);
    std::printf(
        "grab: |target - x| %.3f m at grab, after 400 steps %.3f m (without it %.3f m), "
        "gpu vs cpu %.3g\n",
        glm::length(target - x0), pulled, free, grabbed);
    EXPECT_LT(pulled, 0.5 * free);
    EXPECT_LT(grabbed, kFloatTolerance);
    // Released: the same as a solver that never had a grab, bit for bit.
    run.both([](Solver& solver) { solver.setGrab(std::nullopt); });
    auto neverGrabbed = makeGpuSolver(s);
    neverGrabbed->write(run.gpu->read());
    run.step(200);
    neverGrabbed->step(200);
    EXPECT_EQ(run.gpu->read().positions, neverGrabbed->read().positions);
    EXPECT_LT(run.difference(extent), kFloatTolerance);
    EXPECT_THROW(run.gpu->setGrab(Grab{g.count(), target, 1.0}), std::invalid_argument);
}

// Explicit Euler from rest with no other force: x2 − x0 = Δt²·K·(target − x0)/m exactly as on
// the CPU float backend (the grab is part of F, not a position constraint).
TEST_F(GpuControls, GrabForceIsKTimesDistance) {
    Json j = baseJson();
    j["gravity"] = {0, 0, 0};
    j["damping"] = 0;
    j.erase("wind");
    j.erase("colliders");
    const Scene s = sceneOf(j, "grab law");
    const std::int64_t k = s.grid().index(5, 7);
    Pair run(s);
    const glm::dvec3 x0 = run.gpu->read().positions[k], target = x0 + glm::dvec3(0, 1, 0);
    run.both([&](Solver& solver) { solver.setGrab(Grab{k, target, 2.0}); });
    run.step(2);
    const double dy = run.gpu->read().positions[k].y - x0.y;
    const double expected = s.integrator.dt * s.integrator.dt * 2.0 / s.cloth.mass;
    EXPECT_NEAR(dy, expected, 1e-6 * expected + 4 * std::abs(x0.y) * 0x1p-24);
    EXPECT_LT(run.difference(s.grid().extent()), kFloatTolerance);
}

// The scene `changed` differs from baseJson() in every runtime parameter: stiffnesses, damping,
// mass, gravity, wind, the sphere, Δt and max_speed.
Json changedJson(const Json& sphere) {
    Json j = baseJson(sphere);
    j["springs"] = {{"structural", 300.0}, {"shear", 40.0}, {"bend", 12.0}};
    j["damping"] = 4.5;
    j["cloth"]["mass"] = 0.6;
    j["gravity"] = {-0.5, -8.0, 0.4};
    j["wind"] = {{"direction", {-0.3, 0.1, 1.0}}, {"strength", 3.5}};
    Json& sphereJson = j["colliders"][0];
    sphereJson["radius"] = sphereJson["radius"].get<double>() * 1.4;
    sphereJson["center"][1] = sphereJson["center"][1].get<double>() - 0.05;
    j["integrator"]["dt"] = 0.0008;
    j["max_speed"] = 500.0;
    return j;
}

// setParameters at step 0 equals a solver built with the new scene, bit for bit (same kernels,
// same floats); mid-run it matches the CPU float backend that got the same call.
void expectSetParametersMatches(const Json& sphere, double tolerance) {
    const Scene s = sceneOf(baseJson(sphere), "before"), t = sceneOf(changedJson(sphere), "after");
    const double extent = s.grid().extent();
    auto live = makeGpuSolver(s), fresh = makeGpuSolver(t), unchanged = makeGpuSolver(s);
    live->setParameters(t);
    live->step(300);
    fresh->step(300);
    unchanged->step(300);
    EXPECT_EQ(live->read().positions, fresh->read().positions);
    EXPECT_EQ(live->read().velocities, fresh->read().velocities);
    const double effect = maxDifferenceOverExtent(live->read(), unchanged->read(), extent);
    EXPECT_GT(effect, 1e-3) << "the change should matter";

    Pair run(s);
    run.step(150);
    run.both([&](Solver& solver) { solver.setParameters(t); });
    // The time goes on from where it was (docs/colliders.md §3): 150 steps of the old Δt.
    EXPECT_DOUBLE_EQ(run.gpu->time(), 150 * s.integrator.dt);
    EXPECT_DOUBLE_EQ(run.cpu->time(), 150 * s.integrator.dt);
    run.step(300);
    const double d = run.difference(extent);
    std::printf("setParameters (sphere %s): effect %.3g, gpu vs cpu %.3g (/ extent)\n",
                sphere.dump().c_str(), effect, d);
    EXPECT_LT(d, tolerance);
}

TEST_F(GpuControls, SetParametersMatchesAFreshSolverAndTheCpu) {
    expectSetParametersMatches(kFarSphere, kFloatTolerance);
}

// The cloth lands on the sphere, so its new radius and centre are what the kernels use.
TEST_F(GpuControls, SetParametersMovesTheSphereTheClothRestsOn) {
    expectSetParametersMatches(kNearSphere, kContactTolerance);
}

// What the kernels were compiled for cannot change: another grid, other features, other pins
// or another collider order is refused (std::invalid_argument) and leaves the solver as it was.
TEST_F(GpuControls, SetParametersRefusesWhatWouldNeedAnotherSolver) {
    const Json base = baseJson();
    const Scene s = sceneOf(base, "base");
    auto solver = makeGpuSolver(s), untouched = makeGpuSolver(s);
    const std::vector<std::pair<const char*, std::function<void(Json&)>>> refused = {
        {"grid",
         [](Json& j) {
             j["cloth"]["resolution"] = {20, 13};
         }},
        {"no bend", [](Json& j) { j["springs"].erase("bend"); }},
        {"no wind", [](Json& j) { j.erase("wind"); }},
        {"wind strength 0", [](Json& j) { j["wind"]["strength"] = 0.0; }},
        {"another collider", [](Json& j) { j["colliders"].push_back(kPlane); }},
        {"pins",
         [](Json& j) {
             j["pins"] = {{0, -1}};
         }},
    };
    for (const auto& [what, edit] : refused) {
        Json j = base;
        edit(j);
        EXPECT_THROW(solver->setParameters(sceneOf(j, what)), std::invalid_argument) << what;
    }
    // Same features, other order: the order is compiled into the kernel (docs/gpu.md).
    Json twoColliders = base;
    twoColliders["colliders"].push_back(kPlane);
    Json swapped = twoColliders;
    swapped["colliders"] = {kPlane, kFarSphere};
    auto ordered = makeGpuSolver(sceneOf(twoColliders, "sphere, plane"));
    EXPECT_THROW(ordered->setParameters(sceneOf(swapped, "plane, sphere")), std::invalid_argument);
    // A pin set at run time is part of the solver's pins.
    solver->setPinned(3, 3, true);
    EXPECT_THROW(solver->setParameters(s), std::invalid_argument);
    solver->setPinned(3, 3, false);
    solver->setParameters(s);  // the scene's own again: accepted
    solver->step(300);
    untouched->step(300);
    EXPECT_EQ(solver->read().positions, untouched->read().positions);
}

}  // namespace
}  // namespace cloth::test
