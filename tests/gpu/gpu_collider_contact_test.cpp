// Contact laws of docs/colliders.md on the GPU solver, mirroring
// tests/cpu/collider_solver_test.cpp: Coulomb friction holds a cloth on a tilted box below the
// friction angle and lets it slide above; a moving box carries the cloth resting on it;
// setParameters moves colliders and changes their thickness and friction without a new kernel; a
// mesh grid beyond one SSBO is an input error.
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <regex>

#include "gpu/gpu_collider_table.h"
#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "model/errors.h"
#include "support/collider_cases.h"
#include "support/contact_scenes.h"

namespace cloth::test {
namespace {

namespace fs = std::filesystem;

// How far the centre of clothOnTiltedBox(degrees, friction) moves in 1 s [m] on the GPU
// (support/contact_scenes.h: its springs keep explicit Euler inside its bound, so that a sliding
// cloth does not blow up).
double slideOnTiltedBox(double degrees, double friction, StepDispatch dispatch) {
    const Scene s = parseScene(clothOnTiltedBox(degrees, friction).dump(), "tilted box (test)");
    GpuOptions options;
    options.dispatch = dispatch;
    auto solver = makeGpuSolver(s, options);
    const glm::dvec3 start = meanOf(solver->read().positions);
    const StepResult r = solver->step(s.defaultSteps());
    EXPECT_FALSE(r.unstable) << r.reason << " at step " << r.firstBadStep;
    return glm::length(meanOf(solver->read().positions) - start);
}

class GpuColliderContact : public GpuTest {};

// Law (Coulomb, docs/colliders.md §2): a cloth on a slope holds below the friction angle
// atan(c_f) and slides above it, on the GPU as on the CPU.
TEST_F(GpuColliderContact, ClothHoldsBelowTheFrictionAngleAndSlidesAbove) {
    for (double cf : {0.3, 0.6, 1.0}) {
        const double angle = std::atan(cf) * 180 / std::numbers::pi;
        for (StepDispatch d : {StepDispatch::PerStep, StepDispatch::ManySteps}) {
            const double below = slideOnTiltedBox(angle - 3, cf, d);
            const double above = slideOnTiltedBox(angle + 3, cf, d);
            std::printf(
                "gpu %-10s friction %.1f (atan %.2f°): centre moves %.3g m in 1 s at %.2f°, "
                "%.3g m at %.2f°\n",
                stepDispatchName(d), cf, angle, below, angle - 3, above, angle + 3);
            EXPECT_LT(below, 0.01) << "c_f " << cf << ": slid below the friction angle";
            EXPECT_GT(above, 0.05) << "c_f " << cf << ": held above the friction angle";
        }
    }
}

// Law: static friction carries the cloth with a moving collider (v = v_c at a sticking
// contact), posed by the batch of poses the host uploads.
TEST_F(GpuColliderContact, MovingBoxCarriesTheClothRestingOnIt) {
    const Scene s = parseScene(clothOnMovingBox().dump(), "moving box (test)");
    auto solver = makeGpuSolver(s);
    // Uneven calls, so that runs of steps straddle the pose batches.
    for (long n : {1L, 63L, 70L, 200L, 666L}) ASSERT_FALSE(solver->step(n).unstable);
    const SimState st = solver->read();
    const glm::dvec3 v = meanOf(st.velocities);
    const double minY = lowestY(st.positions);
    std::printf("gpu: box at 0.3 m/s: cloth's mean velocity after 1 s (%.4f, %.4f, %.4f) m/s\n",
                v.x, v.y, v.z);
    EXPECT_NEAR(v.x, 0.3, 0.01);
    EXPECT_NEAR(v.z, 0.0, 0.01);
    EXPECT_GT(minY, 0.1 + 0.002 - 1e-5) << "the cloth sank into the box";
}

// Law (Coulomb, static friction) under implicit Euler's stick and slip (src/model/solve_contact.h,
// cg_grip.comp): the sheet wrapped off-centre over a sphere is held against its own tension at
// Δt = 1/60 s on the GPU, within 1 cm (mean height) of the CPU in float; and a cloth on a
// moving box is carried at the box's speed, held at v_c.
TEST_F(GpuColliderContact, ImplicitStaticFrictionHoldsAsOnTheCpu) {
    const Scene s = parseScene(
        sheetOverSphere(0.8, {{"method", "implicit_euler"}, {"dt", 1.0 / 60}}).dump(), "test");
    std::unique_ptr<Solver> gpu = makeGpuSolver(s);
    std::unique_ptr<Solver> cpu = makeCpuSolver(s, {Precision::Float, 1});
    for (Solver* solver : {gpu.get(), cpu.get()}) ASSERT_FALSE(solver->step(90).unstable);
    const double onGpu = meanOf(gpu->read().positions).y, onCpu = meanOf(cpu->read().positions).y;
    std::printf(
        "sheet over a sphere, implicit Euler at 1/60 s, 1.5 s: mean height gpu %.4f m, "
        "cpu float %.4f m\n",
        onGpu, onCpu);
    EXPECT_GT(onGpu, 0.4);
    EXPECT_NEAR(onGpu, onCpu, 0.01);

    Json carried = clothOnMovingBox();
    carried["integrator"] = {{"method", "implicit_euler"}, {"dt", 1.0 / 60}};
    const Scene box = parseScene(carried.dump(), "moving box, implicit (test)");
    gpu = makeGpuSolver(box);
    ASSERT_FALSE(gpu->step(box.defaultSteps()).unstable);
    const glm::dvec3 v = meanOf(gpu->read().velocities);
    std::printf(
        "gpu implicit: box at 0.3 m/s: cloth's mean velocity after 1 s (%.4f, %.4f, "
        "%.4f) m/s\n",
        v.x, v.y, v.z);
    // Held at v_c, not merely dragged along: with the hold's v_c taken as 0 it was 0.2903.
    EXPECT_NEAR(v.x, 0.3, 1e-3);
    EXPECT_NEAR(v.z, 0.0, 1e-3);
}

// Law (Coulomb) under vbd's friction, an energy of each vertex's local problem with the normal
// force of its last projection (vbd_sweep.comp): on a slope the cloth holds 3° below the
// friction angle and slides as on the CPU in float 5° above; the sheet wrapped over a sphere
// stays on it; a moving box carries the cloth at its speed (Δt = 1/60 s throughout).
TEST_F(GpuColliderContact, VbdFrictionActsAsOnTheCpu) {
    const Json vbd = {{"method", "vbd"}, {"dt", 1.0 / 60}, {"iterations", 10}};
    auto both = [&](Json j, const char* what, long steps) {
        j["integrator"] = vbd;
        const Scene s = parseScene(j.dump(), what);
        std::unique_ptr<Solver> gpu = makeGpuSolver(s);
        std::unique_ptr<Solver> cpu = makeCpuSolver(s, {Precision::Float, 1});
        const glm::dvec3 start = meanOf(cpu->read().positions);
        for (Solver* solver : {gpu.get(), cpu.get()}) EXPECT_FALSE(solver->step(steps).unstable);
        return std::array<glm::dvec3, 3>{meanOf(gpu->read().positions) - start,
                                         meanOf(cpu->read().positions) - start,
                                         meanOf(gpu->read().velocities)};
    };
    const double angle = std::atan(0.5) * 180 / std::numbers::pi;
    const auto held = both(clothOnTiltedBox(angle - 3, 0.5), "slope (test)", 60);
    const auto slid = both(clothOnTiltedBox(angle + 5, 0.5), "slope (test)", 60);
    const double heldGpu = glm::length(held[0]), slidGpu = glm::length(slid[0]);
    const double slidCpu = glm::length(slid[1]);
    std::printf("gpu vbd, c_f 0.5: %.2f° moved %.3g m; %.2f° slid %.4f m (cpu float %.4f m)\n",
                angle - 3, heldGpu, angle + 5, slidGpu, slidCpu);
    EXPECT_LT(heldGpu, 0.002);
    EXPECT_NEAR(slidGpu, slidCpu, 0.005 * slidCpu);

    const auto sphere = both(sheetOverSphere(0.8, vbd), "sheet over a sphere (test)", 90);
    const double top = 0.7;  // the sheet's starting height
    std::printf("gpu vbd: sheet over a sphere after 1.5 s: mean height %.4f m (cpu float %.4f m)\n",
                top + sphere[0].y, top + sphere[1].y);
    EXPECT_GT(top + sphere[0].y, 0.4);
    EXPECT_NEAR(sphere[0].y, sphere[1].y, 0.01);

    const auto carried = both(clothOnMovingBox(), "moving box (test)", 60);
    std::printf("gpu vbd: box at 0.3 m/s: cloth's mean velocity (%.4f, %.4f, %.4f) m/s\n",
                carried[2].x, carried[2].y, carried[2].z);
    EXPECT_NEAR(carried[2].x, 0.3, 1e-3);
    EXPECT_NEAR(carried[2].z, 0.0, 1e-3);
}

// Invariant (inelastic contact) under implicit Euler and vbd on the GPU, as on the CPU
// (tests/cpu/implicit_contact_test.cpp): a sheet started 1 cm under a plane leaves it at rest; one
// a rising plane pushes moves up with it.
TEST_F(GpuColliderContact, LargeStepContactLeavesAVertexThatStartedInsideAtRest) {
    for (const char* method : {"implicit_euler", "vbd"}) {
        auto solver = makeGpuSolver(parseScene(sheetUnderPlane(0.01, 0, method).dump(), "test"));
        ASSERT_FALSE(solver->step(1).unstable);
        double fastest = 0;
        for (const glm::dvec3& v : solver->read().velocities)
            fastest = std::max(fastest, glm::length(v));
        solver = makeGpuSolver(parseScene(sheetUnderPlane(0, 0.5, method).dump(), "test"));
        ASSERT_FALSE(solver->step(100).unstable);
        const double rising = meanOf(solver->read().velocities).y;
        std::printf(
            "gpu %s: started 1 cm inside, fastest %.3g m/s after a step; pushed by a "
            "plane rising at 0.5 m/s: %.4f m/s\n",
            method, fastest, rising);
        EXPECT_LT(fastest, 0.01) << method;
        EXPECT_NEAR(rising, 0.5, 1e-3) << method;
    }
}

// The poses of a step do not depend on how the steps are grouped into calls, status reads and
// pose batches: runs of many steps longer than a batch (checkEvery 200), one step per call, and
// runs that straddle batches give the same bits.
TEST_F(GpuColliderContact, PoseBatchesDoNotDependOnHowStepsAreGrouped) {
    const fs::path dir = freshTempDir("GpuColliderContact", "grouping");
    writeSlabObj(dir);
    const Scene s = parseScene(
        fallingClothOnColliders(colliderCases().back().colliders, "explicit_euler").dump(),
        (dir / "scene.json").string());
    auto run = [&](StepDispatch dispatch, int checkEvery, const std::vector<long>& calls) {
        GpuOptions options;
        options.dispatch = dispatch;
        options.checkEvery = checkEvery;
        auto solver = makeGpuSolver(s, options);
        for (long n : calls) EXPECT_FALSE(solver->step(n).unstable);
        return solver->read();
    };
    for (StepDispatch d : {StepDispatch::PerStep, StepDispatch::ManySteps}) {
        const SimState whole = run(d, 64, {300});
        EXPECT_EQ(run(d, 200, {300}).positions, whole.positions) << stepDispatchName(d);
        EXPECT_EQ(run(d, 7, {1, 63, 2, 100, 134}).positions, whole.positions)
            << stepDispatchName(d);
        EXPECT_EQ(run(d, 64, std::vector<long>(300, 1)).velocities, whole.velocities)
            << stepDispatchName(d);
    }
}

// setParameters takes a collider's new placement, thickness, friction and motion speed as data:
// the solver then steps exactly as a new solver of the new scene given the same state.
TEST_F(GpuColliderContact, SetParametersMovesCollidersAndChangesTheirContact) {
    const fs::path dir = freshTempDir("GpuColliderContact", "set_parameters");
    writeSlabObj(dir);
    const Json all = colliderCases().back().colliders;
    Json moved = all;
    moved[0]["center"] = {0.0, 0.72, 0.02};
    moved[0]["thickness"] = 0.02;
    moved[0]["friction"] = 0.9;
    moved[1]["motion"]["degrees_per_second"] = -45;
    moved[2]["translation"] = {0.05, 0.74, 0};
    moved[2]["thickness"] = 0.01;
    moved[3]["radius"] = 0.15;
    moved[4]["motion"]["velocity"] = {0, 0.2, 0};
    auto scene = [&](const Json& colliders) {
        return parseScene(fallingClothOnColliders(colliders, "explicit_euler").dump(),
                          (dir / "scene.json").string());
    };
    const Scene before = scene(all), after = scene(moved);
    auto solver = makeGpuSolver(before);
    ASSERT_FALSE(solver->step(300).unstable);
    solver->setParameters(after);
    solver->resetStepCount();  // both solvers pose the colliders at the same times
    auto fresh = makeGpuSolver(after);
    fresh->write(solver->read());
    ASSERT_FALSE(solver->step(500).unstable);
    ASSERT_FALSE(fresh->step(500).unstable);
    EXPECT_EQ(solver->read().positions, fresh->read().positions);
    EXPECT_EQ(solver->read().velocities, fresh->read().velocities);
}

// The kernel text of a scene with `colliders`, without // comments: what is left is code.
std::string integrateKernel(const Json& colliders, const fs::path& dir) {
    const Scene s = parseScene(fallingClothOnColliders(colliders, "explicit_euler").dump(),
                               (dir / "scene.json").string());
    const std::string text =
        assembleKernel(CLOTH_SOURCE_DIR "/shaders", "compute/integrate.comp", s, {}).text;
    return std::regex_replace(text, std::regex("//[^\n]*"), "");
}

// DESIGN.md §3: a scene compiles the collider code it declares and nothing else; a plain plane
// takes the one contact response (with zero thickness, friction and speed) and nothing else.
TEST(GpuColliderVariant, EachSceneCompilesOnlyItsColliders) {
    const fs::path dir = freshTempDir("GpuColliderVariant", "kernels");
    writeSlabObj(dir);
    const std::vector<ColliderCase> cases = colliderCases();
    auto named = [&](const std::string& name) {
        for (const ColliderCase& c : cases)
            if (c.name == name) return c.colliders;
        return Json();
    };
    const Json plain = {{{"type", "plane"}, {"point", {0, 0, 0}}, {"normal", {0, 1, 0}}}};
    struct Expect {
        Json colliders;
        std::vector<const char*> present, absent;
    };
    const std::vector<Expect> expects = {
        {plain,
         {"respondPlane(", "planeContact("},
         {"sphereContact", "respondSphere", "boxContact", "capsuleContact", "gridContact",
          "colliderVelocity", "POSE_BATCH"}},
        {named("box"),
         {"boxContact(", "STILL(collideBoxRecord, 0)"},
         {"respondPlane(", "capsuleContact(", "gridContact(", "colliderVelocity("}},
        {named("mesh"), {"gridContact(", "sdfValue("}, {"boxContact(", "colliderVelocity("}},
        {named("capsule_turning"),
         {"capsuleContact(", "colliderVelocity(", "POSE_BATCH 64",
          "MOVING(collideCapsuleRecord, pose + 0, pose + 3)"},
         {"boxContact(", "gridContact("}},
    };
    for (const Expect& e : expects) {
        const std::string text = integrateKernel(e.colliders, dir);
        for (const char* p : e.present)
            EXPECT_NE(text.find(p), std::string::npos) << e.colliders << ": no '" << p << "'";
        for (const char* a : e.absent)
            EXPECT_EQ(text.find(a), std::string::npos) << e.colliders << ": '" << a << "'";
    }
}

// A mesh grid larger than one SSBO binding is an input error naming the mesh's cell, before
// anything is allocated (gpu::ColliderTable::checkFits).
TEST(GpuColliderTable, AGridBeyondOneSsboNamesTheMeshCell) {
    const fs::path dir = freshTempDir("GpuColliderTable", "fits");
    writeSlabObj(dir);
    const Scene s = parseScene(
        fallingClothOnColliders(colliderCases().back().colliders, "explicit_euler").dump(),
        (dir / "scene.json").string());
    const gpu::ColliderTable table(s);
    const long long bytes = (long long)(table.vec4Count()) * 16;
    EXPECT_NO_THROW(table.checkFits(bytes, s.source));
    try {
        table.checkFits(bytes - 1, s.source);
        FAIL() << "a table one byte too large was accepted";
    } catch (const InputError& e) {
        EXPECT_EQ(e.key(), "colliders[2].cell") << e.what();
    }
}

}  // namespace
}  // namespace cloth::test
