// The GPU backend against the double-precision reference (DESIGN.md §6) and the CPU float
// backend: each spring family alone and together, wind, each collider and their order, pins
// given with negative indices, the seed's 1×2 spring and 1×3 chain, and grids whose sides are
// not multiples of the 16×16 work group (37×53, 1×257, 257×1).
#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>

#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

constexpr long kSteps = 200;
constexpr double kReferenceTolerance = 1e-4;  // max |p − p_ref| / extent, the parity bound
// Two float backends whose roundings differ in order (FMA contraction, sqrt): ~1e-7 seen on
// smooth physics. A sphere contact turns last-bit differences into "inside or not" decisions
// worth up to Δt²|g| each (~1e-5 m seen): there the reference tolerance applies.
constexpr double kCpuFloatTolerance = 1e-6;
constexpr double kCpuFloatContactTolerance = kReferenceTolerance;

// A cloth that starts tilted and falls: Δt inside explicit Euler's bound Δt < μ/λ_max
// (DESIGN.md §2), λ_max ≤ 2·4·(200 + 80 + 20) = 2400 N/m, μ = 3 → 1.25 ms > 1 ms.
// Colliders are axis-aligned at dyadic heights so float and double project alike (see
// tests/cpu/reference_parity_test.cpp).
Json baseScene() {
    return Json::parse(R"({
      "name": "gpu-parity",
      "cloth": { "resolution": [19, 13], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
      "springs": { "structural": 200.0, "shear": 80.0, "bend": 20.0 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]],
      "integrator": { "method": "explicit_euler", "dt": 0.001 }
    })");
}

const Json kPlane = {{"type", "plane"}, {"point", {0, 1.125, 0}}, {"normal", {0, 1, 0}}};
const Json kSphere = {{"type", "sphere"}, {"center", {0.05, 0.9, 0.0}}, {"radius", 0.3}};
const Json kWind = {{"direction", {1, 0.2, 0.6}}, {"strength", 2.0}};

struct Case {
    std::string name;
    std::function<void(Json&)> edit;
};
// gtest prints a parameter in test listings; the name says which case it is.
void PrintTo(const Case& c, std::ostream* os) {
    *os << c.name;
}

void springsOnly(Json& j, const char* family) {
    j["springs"] = Json::object({{family, j["springs"][family]}});
}

void chain(Json& j, int nu, int nv) {
    j["cloth"]["resolution"] = {nu, nv};
    j["cloth"]["size"] = {2.0, 2.0};
    j["cloth"]["u_axis"] = nu > 1 ? Json{1, -0.2, 0} : Json{1, 0, 0};
    j["cloth"]["v_axis"] = nv > 1 ? Json{0.1, -1, 0} : Json{0, 0, 1};
    j["pins"] = {{0, 0}};
}

std::vector<Case> cases() {
    return {
        {"structural", [](Json& j) { springsOnly(j, "structural"); }},
        {"shear", [](Json& j) { springsOnly(j, "shear"); }},
        {"bend", [](Json& j) { springsOnly(j, "bend"); }},
        {"all_families", [](Json&) {}},
        {"wind", [](Json& j) { j["wind"] = kWind; }},
        {"plane", [](Json& j) { j["colliders"] = Json::array({kPlane}); }},
        {"sphere", [](Json& j) { j["colliders"] = Json::array({kSphere}); }},
        {"plane_then_sphere",
         [](Json& j) {
             j["colliders"] = {kPlane, kSphere};
         }},
        {"sphere_then_plane",
         [](Json& j) {
             j["colliders"] = {kSphere, kPlane};
         }},
        {"negative_pins",
         [](Json& j) {
             j["pins"] = {{-1, -1}, {0, -1}, {-10, -1}, {-1, 0}};
         }},
        {"grid_37x53",
         [](Json& j) {
             j["cloth"]["resolution"] = {37, 53};
             j["wind"] = kWind;
         }},
        {"grid_1x257", [](Json& j) { chain(j, 1, 257); }},
        {"grid_257x1", [](Json& j) { chain(j, 257, 1); }},
    };
}

Scene sceneFor(const Case& c) {
    Json j = baseScene();
    c.edit(j);
    j["name"] = c.name;
    return parseScene(j.dump(), "gpu parity case " + c.name);
}

class GpuParity : public GpuTest, public ::testing::WithParamInterface<Case> {};

void expectMatchesReference(const Scene& scene) {
    const ref::Simulation expected = runReference(scene, kSteps);
    const double dev =
        maxDeviationOverExtent(runGpu(scene, kSteps), expected, scene.grid().extent());
    std::printf("%-18s %4dx%-4d max |p_gpu - p_ref| / extent = %.3g\n", scene.name.c_str(),
                scene.cloth.nu, scene.cloth.nv, dev);
    EXPECT_LT(dev, kReferenceTolerance) << scene.name;
}

TEST_P(GpuParity, MatchesTheReferenceAfter200Steps) {
    expectMatchesReference(sceneFor(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Scenes, GpuParity, ::testing::ValuesIn(cases()),
                         [](const auto& p) { return p.param.name; });

class GpuShippedParity : public GpuTest {};

// The seed's single 3D spring (1×2) and its chain of two coupled springs (1×3).
TEST_F(GpuShippedParity, SpringAndChainMatchTheReference) {
    for (const char* name : {"spring", "chain"}) expectMatchesReference(loadShippedScene(name));
}

// The collider cases must exercise what they claim, and their order must matter.
TEST_F(GpuShippedParity, ColliderCasesTouchTheirCollidersAndOrderMatters) {
    std::map<std::string, Scene> scenes;
    for (const Case& c : cases()) scenes.emplace(c.name, sceneFor(c));
    const ref::Simulation free = runReference(scenes.at("all_families"), kSteps);
    for (const char* name : {"plane", "sphere"}) {
        const double moved = maxDeviationOverExtent(runGpu(scenes.at(name), kSteps), free, 1.0);
        EXPECT_GT(moved, 1e-2) << name << " collider never touched";
    }
    const SimState a = runGpu(scenes.at("plane_then_sphere"), kSteps);
    const SimState b = runGpu(scenes.at("sphere_then_plane"), kSteps);
    EXPECT_GT(maxDifferenceOverExtent(a, b, 1.0), 1e-3) << "collider order had no effect";
}

class GpuCpuParity : public GpuTest {};

// The same float physics on two backends: a 37×53 grid with every force, and each collider.
// (A vertex pressed between two overlapping colliders chatters, and which of two correct
// roundings wins there is a coin toss two float backends call differently: up to ~1e-4 of the
// extent after 200 steps, as the *_then_* cases show against the reference. Hence one collider
// at a time here.)
TEST_F(GpuCpuParity, MatchesTheCpuFloatBackend) {
    for (const Json& colliders : {Json::array(), Json::array({kPlane}), Json::array({kSphere})}) {
        Json j = baseScene();
        j["cloth"]["resolution"] = {37, 53};
        j["wind"] = kWind;
        j["colliders"] = colliders;
        const Scene scene = parseScene(j.dump(), "gpu-cpu parity");
        const double d = maxDifferenceOverExtent(runGpu(scene, kSteps), runCpuFloat(scene, kSteps),
                                                 scene.grid().extent());
        std::printf("37x53 all forces, colliders %s: max |p_gpu - p_cpu_float| / extent = %.3g\n",
                    colliders.dump().c_str(), d);
        EXPECT_LT(d, colliders.empty() ? kCpuFloatTolerance : kCpuFloatContactTolerance)
            << colliders.dump();
    }
}

// DESIGN.md §3: a feature the scene does not declare is not compiled. Dropping one must change
// the GPU result exactly as dropping it changes the CPU's.
TEST_F(GpuCpuParity, DroppingAFeatureChangesTheResultAsOnTheCpu) {
    Json full = baseScene();
    full["wind"] = kWind;
    full["colliders"] = Json::array({kSphere});
    const std::vector<std::pair<std::string, std::function<void(Json&)>>> drops = {
        {"shear", [](Json& j) { j["springs"].erase("shear"); }},
        {"bend", [](Json& j) { j["springs"].erase("bend"); }},
        {"wind", [](Json& j) { j.erase("wind"); }},
        {"sphere", [](Json& j) { j.erase("colliders"); }},
    };
    const Scene fullScene = parseScene(full.dump(), "full");
    const double extent = fullScene.grid().extent();
    const SimState gpuFull = runGpu(fullScene, kSteps), cpuFull = runCpuFloat(fullScene, kSteps);
    for (const auto& [name, drop] : drops) {
        Json j = full;
        drop(j);
        const Scene dropped = parseScene(j.dump(), "without " + name);
        const SimState gpu = runGpu(dropped, kSteps), cpu = runCpuFloat(dropped, kSteps);
        double effect = 0, mismatch = 0;
        for (std::size_t k = 0; k < gpu.positions.size(); ++k) {
            const glm::dvec3 dGpu = gpuFull.positions[k] - gpu.positions[k];
            const glm::dvec3 dCpu = cpuFull.positions[k] - cpu.positions[k];
            effect = std::max(effect, glm::length(dCpu));
            mismatch = std::max(mismatch, glm::length(dGpu - dCpu));
        }
        std::printf("drop %-7s effect %.3g, gpu vs cpu effect mismatch %.3g (/ extent)\n",
                    name.c_str(), effect / extent, mismatch / extent);
        EXPECT_GT(effect / extent, 1e-4) << name << ": dropping it should matter";
        EXPECT_LT(mismatch / extent, 10 * kCpuFloatTolerance) << name;
    }
}

}  // namespace
}  // namespace cloth::test
