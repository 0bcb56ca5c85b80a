// The viewer's controls under every integrator on the GPU (write, setPinned, setGrab,
// setParameters): after each, the run goes on exactly as a fresh solver given the same state
// and the same control. For verlet this is the check that the forces kept from the last step
// are discarded (docs/integrators.md): a kept F(x) of the old stiffness, grab or state would
// make the first step differ.
#include <functional>
#include <nlohmann/json.hpp>

#include "gpu/gpu_test_support.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

// A small cloth with every feature (wind, a sphere under it, two pins), Δt inside every
// scheme's bound (explicit Euler's μ/λ_max ≥ 1.25 ms).
Scene clothScene(Method method, double structural = 200) {
    Json j = Json::parse(R"({
      "name": "gpu-integrator-controls",
      "cloth": { "resolution": [11, 7], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                 "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
      "damping": 3.0,
      "gravity": [0.3, -9.81, 0.1],
      "pins": [[0, -1], [-1, -1]],
      "wind": { "direction": [1, 0.2, 0.6], "strength": 2.0 },
      "colliders": [ { "type": "sphere", "center": [0.05, 0.9, 0.0], "radius": 0.3 } ]
    })");
    j["springs"] = {{"structural", structural}, {"shear", 80.0}, {"bend", 20.0}};
    j["integrator"] = {{"method", methodName(method)}, {"dt", 1e-3}};
    return parseScene(j.dump(), "gpu integrator controls (test)");
}

struct Control {
    std::string name;
    // The scene the run continues with (setParameters' argument, else the scene itself).
    std::function<Scene(Method)> sceneAfter;
    // Applied to the running solver, and to the fresh one before or after the state is written
    // into it. Before, where that is the same: then the forces write() computes for the renderer
    // are already right, and the fresh run does not depend on what the running one must get
    // right (dropping its kept forces).
    std::function<void(Solver&, const Scene&)> apply;
    bool beforeWrite = false;
};

std::vector<Control> controls() {
    auto same = [](Method m) { return clothScene(m); };
    return {
        {"set_parameters",
         [](Method m) {
             Scene s = clothScene(m, 350);
             s.integrator.dt = 8e-4;
             s.damping = 2.5;
             s.gravity = {0, -9.81, 0.5};
             return s;
         },
         nullptr},
        {"set_grab", same,
         [](Solver& solver, const Scene& s) {
             solver.setGrab(Grab{s.grid().index(5, 2), {0.0, 1.3, 0.1}, 40.0});
         },
         true},
        {"set_pinned", same, [](Solver& solver, const Scene&) { solver.setPinned(5, 3, true); }},
        {"write", same,
         [](Solver& solver, const Scene&) {
             SimState s = solver.read();
             for (glm::dvec3& x : s.positions) x.y += 0.05 * x.x;  // a sheared state
             solver.write(s);
         }},
    };
}

struct Case {
    Method method;
    Control control;
};
void PrintTo(const Case& c, std::ostream* os) {
    *os << methodName(c.method) << "/" << c.control.name;
}

class GpuIntegratorControls : public GpuTest, public ::testing::WithParamInterface<Case> {};

TEST_P(GpuIntegratorControls, RunGoesOnAsAFreshSolverWithTheSameState) {
    const auto& [method, control] = GetParam();
    const Scene before = clothScene(method), after = control.sceneAfter(method);
    std::unique_ptr<Solver> running = makeGpuSolver(before);
    ASSERT_FALSE(running->step(60).unstable);  // verlet now holds F(x) of the last step
    std::unique_ptr<Solver> fresh = makeGpuSolver(after);
    if (control.apply && control.beforeWrite) control.apply(*fresh, after);
    fresh->write(running->read());
    if (control.apply && !control.beforeWrite) control.apply(*fresh, after);
    if (control.apply)
        control.apply(*running, after);
    else
        running->setParameters(after);
    ASSERT_FALSE(running->step(40).unstable);
    ASSERT_FALSE(fresh->step(40).unstable);
    const SimState a = running->read(), b = fresh->read();
    if (method == Method::ImplicitEuler || method == Method::Vbd) {
        // The running solve starts from its last solution, the fresh one from 0 (the warm start,
        // docs/integrators.md): the two agree to the solves' tolerance (1e-5 of |b|), not bit for
        // bit. vbd's running initial guess has v_{n−1} (the adaptive guess), the fresh one's
        // first has not: the sweeps take both to the same step, but the displacement's rounding
        // differs in the last bits, and the translation's levels (vbd's default) step the blocks
        // from those guesses: 9.3e-6, 1.2e-5 and 3.7e-6 m after a new stiffness, a grab and a
        // pin (implicit Euler: 1.5e-6 at most). A control not taken (the grab, a stiffness)
        // moves vertices by centimetres.
        double most = 0;
        for (std::size_t k = 0; k < a.positions.size(); ++k)
            most = std::max(most, glm::length(a.positions[k] - b.positions[k]));
        std::printf("%s: largest |x_running − x_fresh| %.3g m\n", control.name.c_str(), most);
        EXPECT_LT(most, 5e-5);
        return;
    }
    EXPECT_EQ(a.positions, b.positions);  // the same kernels on the same data: bit for bit
    EXPECT_EQ(a.velocities, b.velocities);
}

std::vector<Case> cases() {
    std::vector<Case> all;
    for (Method m : kMethods)
        for (const Control& c : controls()) all.push_back({m, c});
    return all;
}

INSTANTIATE_TEST_SUITE_P(Methods, GpuIntegratorControls, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) {
                             return std::string(methodName(p.param.method)) + "_" +
                                    p.param.control.name;
                         });

}  // namespace
}  // namespace cloth::test
