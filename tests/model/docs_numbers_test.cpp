// The worked numbers of docs/stability.md that come from the model alone (the λ_max estimates and
// the predicted bounds), read from the page and recomputed here, so the page cannot drift from the
// code: each number must equal the code's at the precision the page prints it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "model/stability.h"
#include "scene/scene_loader.h"

namespace cloth {
namespace {

std::string page() {
    std::ifstream in(CLOTH_SOURCE_DIR "/docs/stability.md");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The numbers of the first match of `pattern` in the page; a failure names the missing sentence.
std::vector<double> numbersOf(const std::string& pattern) {
    const std::string text = page();
    std::smatch m;
    if (!std::regex_search(text, m, std::regex(pattern))) {
        ADD_FAILURE() << "docs/stability.md no longer says: " << pattern;
        return {};
    }
    std::vector<double> numbers;
    for (std::size_t i = 1; i < m.size(); ++i) numbers.push_back(std::stod(m[i].str()));
    return numbers;
}

// `printed` is `value` at the page's precision: within half a unit of its last printed digit,
// `digits` significant ones.
void expectPrinted(double printed, double value, int digits, const char* what) {
    const double unit = std::pow(10.0, std::floor(std::log10(std::abs(printed))) - digits + 1);
    EXPECT_LE(std::abs(printed - value), 0.5 * unit + 1e-12 * std::abs(value))
        << what << ": the page says " << printed << ", the code gives " << value;
}

// The page's worked example: the seed's per-vertex hanging cloth (K = 400, 100, 10 N/m, m = 6 g).
const std::string kHanging = CLOTH_SOURCE_DIR "/bench/hanging_per_vertex.json";

TEST(DocsNumbers, HangingClothLambdaEstimatesAndTheAnalyticMode) {
    const auto n =
        numbersOf(R"(24² hanging cloth it gives (\d+) N/m against the analytic (\d+) N/m)"
                  R"([\s\S]*?Gershgorin says (\d+))");
    ASSERT_EQ(n.size(), 3u);
    const Scene scene = loadScene(kHanging);
    const StabilityBound b = estimateStability(scene, 40);
    expectPrinted(n[0], b.lambdaPower, 4, "power iteration");
    // The stiffest in-plane mode, (−1)^i along û: 4K_structural + 4K_shear.
    const double analytic = 4 * scene.springs.structural + 4 * scene.springs.shear;
    expectPrinted(n[1], analytic, 4, "analytic mode");
    EXPECT_LE(b.lambdaPower, analytic * (1 + 1e-9)) << "a Rayleigh quotient exceeds λ_max";
    expectPrinted(n[2], b.lambdaMax, 4, "Gershgorin");
}

// The 12×12 sweep of `bench stability`: every family scaled with K (shear K/4, bend K/40).
Scene sweepScene(double k) {
    auto text = [](double v) { return std::to_string(v); };
    return loadScene(kHanging, {"cloth.resolution=[12,12]", "springs.structural=" + text(k),
                                "springs.shear=" + text(k / 4), "springs.bend=" + text(k / 40)});
}

TEST(DocsNumbers, SweepLambdaPerStiffness) {
    const auto n =
        numbersOf(R"(Gershgorin gives `λ = ([\d.]+) K`, the power iteration `([\d.]+) K`)");
    ASSERT_EQ(n.size(), 2u);
    const double k = 1000;
    const StabilityBound b = estimateStability(sweepScene(k), 40);
    expectPrinted(n[0], b.lambdaMax / k, 3, "Gershgorin / K");
    expectPrinted(n[1], b.lambdaPower / k, 3, "power / K");
}

TEST(DocsNumbers, SweepPredictedBoundsAtK1e3) {
    const auto n = numbersOf(R"(K = 1e3: explicit Euler [\d.e-]+ s \(tight ([\d.e-]+), safe )"
                             R"(([\d.e-]+)\), RK4 [\d.e-]+ s \(tight ([\d.e-]+)\))");
    ASSERT_EQ(n.size(), 3u);
    const StabilityBound b = estimateStability(sweepScene(1e3), 40);
    expectPrinted(n[0], b.tightDt(Method::ExplicitEuler), 3, "explicit Euler, tight");
    expectPrinted(n[1], b.safeDt(Method::ExplicitEuler), 3, "explicit Euler, safe");
    expectPrinted(n[2], b.tightDt(Method::Rk4), 3, "rk4, tight");
}

}  // namespace
}  // namespace cloth
