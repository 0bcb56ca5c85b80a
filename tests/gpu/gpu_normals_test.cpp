// The renderer draws the GPU cloth from the solver's own buffers (Solver::drawBuffers): its
// normals must be the vertex normals (DESIGN.md §2, central differences) of the cloth's positions
// under every integrator. The force pass writes them for the force-based schemes; vbd has no
// force pass, and its step start writes them (vbd_start.comp). Checked at construction and after
// a run: each drawn normal is unit and equals, to float rounding, the normal of the positions
// before the last step or after it (which of the two depends on where the scheme's last force
// pass, or vbd's start, read them). vbd's buffer held zeros before, and the renderer shaded
// its cloth faceted.
#include <GL/glew.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gpu/gpu_test_support.h"
#include "model/forces.h"

namespace cloth::test {
namespace {

using Json = nlohmann::json;

class GpuNormals : public GpuTest {};

std::vector<glm::vec4> drawnNormals(const Solver& solver, std::size_t n) {
    std::vector<glm::vec4> out(n);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, solver.drawBuffers()->normals);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(n * sizeof(glm::vec4)), out.data());
    return out;
}

// The largest angle [rad] between a drawn normal and the nearer of the normals of `a` and `b`.
double worstAngle(const std::vector<glm::vec4>& drawn, const Scene& s, const SimState& a,
                  const SimState& b) {
    const int nu = s.cloth.nu, nv = s.cloth.nv;
    double worst = 0;
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const glm::dvec3 d(drawn[std::size_t(j * nu + i)]);
            double best = 4;
            for (const SimState* st : {&a, &b}) {
                const auto at = [&](int p, int q) {
                    return st->positions[std::size_t(q * nu + p)];
                };
                const glm::dvec3 n = vertexNormal<double>(nu, nv, i, j, at);
                best = std::min(best, std::acos(std::clamp(glm::dot(d, n), -1.0, 1.0)));
            }
            if (std::abs(glm::length(d) - 1) > 1e-5) best = 4;  // zero or not unit
            worst = std::max(worst, best);
        }
    return worst;
}

TEST_F(GpuNormals, EveryIntegratorDrawsTheVertexNormalsOfItsPositions) {
    for (const char* method :
         {"explicit_euler", "symplectic_euler", "verlet", "rk4", "implicit_euler", "vbd"}) {
        Json j = Json::parse(R"({
          "cloth": { "resolution": [11, 7], "size": [1.2, 0.9], "origin": [-0.6, 1.0, -0.45],
                     "u_axis": [1, 0, 0.1], "v_axis": [0, 0.3, 1], "mass": 0.5 },
          "springs": { "structural": 200, "shear": 80, "bend": 20 },
          "damping": 3.0,
          "colliders": [ { "type": "sphere", "center": [0.05, 0.7, 0.0], "radius": 0.3,
                           "thickness": 0.005, "friction": 0.5 } ]
        })");
        const bool large = std::string(method) == "implicit_euler" || std::string(method) == "vbd";
        j["integrator"] = {{"method", method}, {"dt", large ? 1.0 / 60 : 1e-3}};
        const Scene s = parseScene(j.dump(), "gpu normals (test)");
        std::unique_ptr<Solver> solver = makeGpuSolver(s);
        const std::size_t n = std::size_t(s.cloth.nu) * std::size_t(s.cloth.nv);
        const SimState start = solver->read();
        const double atStart = worstAngle(drawnNormals(*solver, n), s, start, start);
        ASSERT_FALSE(solver->step(large ? 29 : 299).unstable);
        const SimState before = solver->read();
        ASSERT_FALSE(solver->step(1).unstable);
        const double after = worstAngle(drawnNormals(*solver, n), s, before, solver->read());
        std::printf("%-16s drawn normals: worst angle %.2g rad at the start, %.2g after a run\n",
                    method, atStart, after);
        EXPECT_LT(atStart, 1e-3) << method;
        EXPECT_LT(after, 1e-3) << method;
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << method;
    }
}

}  // namespace
}  // namespace cloth::test
