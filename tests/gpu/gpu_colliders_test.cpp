// The GLSL collider functions (shaders/colliders/) against their C++ twins in float
// (src/model/collider_shapes.h, collider_contact.h): φ and n of the plane, sphere, box, capsule and
// baked grid, and the response with thickness, friction and collider velocity, over random
// points on the GPU's own compiler and arithmetic.
#include <GL/glew.h>
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "gpu/shader_loader.h"
#include "gpu_test_support.h"
#include "model/collider_contact.h"
#include "support/box_regions.h"
#include "support/draws.h"

namespace cloth {
namespace {

using V3 = glm::vec3;

// A few ulps of values of order 1, and the normal's worse conditioning near kinks.
constexpr float kPhiTol = 2e-6f, kNormalTol = 2e-4f;

struct Shapes {
    PlaneT<float> plane{{0.1f, -0.2f, 0.05f}, glm::normalize(V3(0.2f, 1.0f, -0.3f))};
    SphereT<float> sphere{{0.1f, 0.2f, -0.1f}, 0.45f};
    BoxT<float> box{{0.05f, 0.1f, 0.0f},
                    {0.4f, 0.25f, 0.3f},
                    axisAngle(glm::normalize(V3(1.0f, 2.0f, -0.5f)), 0.6f)};
    CapsuleT<float> capsule{{-0.3f, 0.1f, 0.2f}, {0.4f, -0.2f, -0.1f}, 0.25f};
    SdfGrid grid;
    Mat3<float> gridRotation = axisAngle(glm::normalize(V3(0.0f, 1.0f, 1.0f)), 0.4f);
    V3 gridTranslation{0.1f, 0.0f, -0.05f};
    ContactParamsT<float> params{0.01f, 0.4f};
};

GLuint buffer(const void* data, size_t bytes) {
    GLuint b = 0;
    glGenBuffers(1, &b);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), data, GL_DYNAMIC_COPY);
    return b;
}

// Runs the probe over `in` (p, v, v_c per point) and returns its eight vec4s per point.
std::vector<glm::vec4> probe(const Shapes& s, const std::vector<glm::vec4>& in) {
    const ShaderSource src =
        assembleShader(CLOTH_SOURCE_DIR "/tests/gpu/shaders", "collider_probe.comp", {});
    const GLuint program = compileComputeProgram(src);
    glUseProgram(program);
    const int n = int(in.size() / 3);
    glUniform1i(0, n);
    glUniform3fv(1, 1, &s.plane.point.x);
    glUniform3fv(2, 1, &s.plane.normal.x);
    glUniform4f(3, s.sphere.center.x, s.sphere.center.y, s.sphere.center.z, s.sphere.radius);
    glUniform3fv(4, 1, &s.box.center.x);
    glUniform3fv(5, 1, &s.box.halfExtents.x);
    glUniformMatrix3fv(6, 1, GL_FALSE, &s.box.rotation[0][0]);
    glUniform4f(7, s.capsule.a.x, s.capsule.a.y, s.capsule.a.z, s.capsule.radius);
    glUniform3fv(8, 1, &s.capsule.b.x);
    glUniform4f(9, float(s.grid.origin.x), float(s.grid.origin.y), float(s.grid.origin.z),
                float(s.grid.cell));
    glUniform3i(10, s.grid.count.x, s.grid.count.y, s.grid.count.z);
    glUniformMatrix3fv(11, 1, GL_FALSE, &s.gridRotation[0][0]);
    glUniform3fv(12, 1, &s.gridTranslation.x);
    glUniform2f(13, s.params.thickness, s.params.friction);
    const std::vector<float> values(s.grid.values.begin(), s.grid.values.end());
    const GLuint bufs[3] = {buffer(in.data(), in.size() * sizeof(glm::vec4)),
                            buffer(nullptr, size_t(n) * 8 * sizeof(glm::vec4)),
                            buffer(values.data(), values.size() * sizeof(float))};
    for (GLuint b = 0; b < 3; ++b) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, bufs[b]);
    glDispatchCompute(GLuint((n + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> out(size_t(n) * 8);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, bufs[1]);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(out.size() * sizeof(glm::vec4)),
                       out.data());
    glDeleteBuffers(3, bufs);
    glDeleteProgram(program);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    return out;
}

void expectContact(const glm::vec4& gpu, const ContactT<float>& cpu, bool normal, const char* what,
                   int k, float phiTol = kPhiTol) {
    EXPECT_NEAR(gpu.w, cpu.phi, phiTol) << what << " φ, point " << k;
    if (normal) {
        EXPECT_NEAR(glm::length(V3(gpu) - cpu.normal), 0, kNormalTol) << what << " n, point " << k;
    }
}

// The grid's φ rounds like the others', plus its slope times the rounding of the point's grid
// coordinates u (a pose, a subtraction and a division: a few ulps of |u|, evaluated in another
// order on the GPU). The test's values are random in [-1, 1], so its interpolant rises by up to
// 2 a cell along each axis, 20 m/m, where a baked mesh's rises by 1 m/m: an NVIDIA H200 put 4 of
// 4000 points 2.3e-6 to 3.0e-6 off, past kPhiTol alone.
float gridPhiTol(const SdfGrid& g, const SdfColliderT<float>& c, const V3& pWorld) {
    const V3 u =
        (glm::transpose(c.rotation) * (pWorld - c.translation) - V3(g.origin)) / float(g.cell);
    const float slope = 2.0f;  // the largest step between neighbouring values, per cell
    return kPhiTol + slope * 4.0f * FLT_EPSILON * (std::abs(u.x) + std::abs(u.y) + std::abs(u.z));
}

class GpuColliders : public test::GpuTest {};

// Law: the GLSL functions compute what the C++ header computes, to float rounding, for every
// shape and for the response (away from the contact threshold and the box's kinks, where one
// rounding can decide differently).
TEST_F(GpuColliders, GlslShapesAndResponseMatchTheCppHeader) {
    Shapes s;
    s.grid.origin = {-0.6, -0.5, -0.55};
    s.grid.cell = 0.1;
    s.grid.count = {12, 11, 12};
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int n = 0; n < 12 * 11 * 12; ++n) s.grid.values.push_back(double(u(rng)));
    const SdfColliderT<float> grid{&s.grid, s.gridRotation, s.gridTranslation};
    std::vector<glm::vec4> in;
    const int count = 4000;
    for (int k = 0; k < count; ++k)
        for (const float scale : {0.8f, 2.0f, 0.4f})
            in.emplace_back(scale * test::drawVec3(u, rng), 0.0f);
    const std::vector<glm::vec4> out = probe(s, in);
    int touched = 0;
    for (int k = 0; k < count; ++k) {
        const V3 p(in[3 * size_t(k)]), v(in[3 * size_t(k) + 1]), vc(in[3 * size_t(k) + 2]);
        const glm::vec4* o = &out[8 * size_t(k)];
        expectContact(o[0], contact(s.plane, p), true, "plane", k);
        const ContactT<float> sc = contact(s.sphere, p);
        expectContact(o[1], sc, sc.phi + s.sphere.radius > 1e-2f, "sphere", k);
        const ContactT<float> bc = contact(s.box, p);
        const bool clear = test::clearOfBoxKinks<float>(s.box, p, 1e-2f);
        expectContact(o[2], bc, clear, "box", k);
        const ContactT<float> cc = contact(s.capsule, p);
        expectContact(o[3], cc, cc.phi + s.capsule.radius > 1e-2f, "capsule", k);
        expectContact(o[4], contact(grid, p), true, "grid", k, gridPhiTol(s.grid, grid, p));
        if (!clear || std::abs(bc.phi - s.params.thickness) < 1e-4f) continue;
        V3 pb = p, vb = v;
        const bool hit = collide(s.box, s.params, vc, pb, vb);
        touched += hit;
        EXPECT_EQ(o[5].w, hit ? 1.0f : 0.0f) << k;
        EXPECT_NEAR(glm::length(V3(o[5]) - pb), 0, 1e-5f) << k;
        EXPECT_NEAR(glm::length(V3(o[6]) - vb), 0, 1e-4f) << k;
        V3 ps = p, vs = v;
        if (std::abs(sc.phi - s.params.thickness) > 1e-4f && sc.phi + s.sphere.radius > 1e-2f) {
            collide(s.sphere, s.params, vc, ps, vs);
            EXPECT_NEAR(glm::length(V3(o[7]) - ps), 0, 1e-5f) << k;
        }
    }
    EXPECT_GT(touched, 150);
}

}  // namespace
}  // namespace cloth
