// DESIGN.md §3: the scene decides what is compiled. A feature it does not declare leaves no code
// in the source handed to the GLSL compiler (inspected here as text), and the spring loop walks
// only the declared rows of kSpringOffsets. No GL needed for the text; compiling needs a context.
#include <regex>

#include "gpu/gpu_solver.h"
#include "gpu/gpu_test_support.h"
#include "gpu/gpu_variant.h"
#include "gpu/shader_loader.h"

namespace cloth::test {
namespace {

constexpr const char* kShaderDir = CLOTH_SOURCE_DIR "/shaders";

Scene plainScene() {
    return parseScene(R"({
      "name": "plain",
      "cloth": { "resolution": [8, 5], "size": [1, 1], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1] },
      "springs": { "structural": 100.0 },
      "damping": 0.5,
      "integrator": { "method": "explicit_euler", "dt": 0.001 }
    })",
                      "plain (test)");
}

Scene fullScene() {
    return parseScene(R"({
      "name": "full",
      "cloth": { "resolution": [8, 5], "size": [1, 1], "origin": [0, 0, 0],
                 "u_axis": [1, 0, 0], "v_axis": [0, 0, 1] },
      "springs": { "structural": 100.0, "shear": 50.0, "bend": 10.0 },
      "damping": 0.5,
      "integrator": { "method": "explicit_euler", "dt": 0.001 },
      "pins": [[0, 0]],
      "colliders": [ { "type": "sphere", "center": [0, -1, 0], "radius": 0.5 },
                     { "type": "plane", "point": [0, -2, 0], "normal": [0, 1, 0] } ],
      "wind": { "direction": [1, 0, 0], "strength": 1.0 }
    })",
                      "full (test)");
}

std::string kernelText(const Scene& scene, const char* file) {
    return assembleKernel(kShaderDir, std::string("compute/") + file, scene, {}).text;
}

// Both kernels without their // comments: what is left is code.
std::string bothKernels(const Scene& scene) {
    const std::string text = kernelText(scene, "forces.comp") + kernelText(scene, "integrate.comp");
    return std::regex_replace(text, std::regex("//[^\n]*"), "");
}

TEST(GpuSpecialisation, UndeclaredFeaturesLeaveNoCodeInTheSource) {
    const std::string plain = bothKernels(plainScene());
    // (Params keeps its `wind` member: the block's layout is fixed, its use is not compiled.)
    for (const char* absent : {"windForce", "params.wind", "collide", "Colliders", "colliders[",
                               "PLANE(", "SPHERE(", "HAS_SHEAR", "HAS_BEND"})
        EXPECT_EQ(plain.find(absent), std::string::npos) << "'" << absent << "' in:\n" << plain;
    const std::string full = bothKernels(fullScene());
    for (const char* present : {"windForce", "collidePlane", "collideSphere",
                                "#define COLLIDERS_IN_SCENE_ORDER SPHERE(0) PLANE(1)"})
        EXPECT_NE(full.find(present), std::string::npos) << "'" << present << "' missing";
}

// Pins and the grab are run-time state (Solver::setPinned, setGrab), not features: their code
// is in every variant, and a scene's pins do not change the kernel.
TEST(GpuSpecialisation, PinsAndGrabAreInEveryVariant) {
    for (const Scene& scene : {plainScene(), fullScene()}) {
        const std::string text = bothKernels(scene);
        for (const char* present : {"pins[", "uGrabVertex", "grabForce("})
            EXPECT_NE(text.find(present), std::string::npos) << scene.name << ": " << present;
    }
    Scene unpinned = fullScene();
    unpinned.pins.clear();
    EXPECT_EQ(gpuDefines(unpinned, {}), gpuDefines(fullScene(), {}));
}

// The one spring loop walks the generated table: structural rows only, in kSpringOffsets order.
TEST(GpuSpecialisation, SpringTableHoldsOnlyTheDeclaredFamilies) {
    const std::string plain = kernelText(plainScene(), "forces.comp");
    EXPECT_NE(plain.find("#define NUM_SPRING_OFFSETS 4\n"), std::string::npos);
    EXPECT_NE(plain.find("#define SPRING_OFFSETS ivec4(1, 0, 0, 0), ivec4(-1, 0, 0, 1), "
                         "ivec4(0, 1, 0, 2), ivec4(0, -1, 0, 3)\n"),
              std::string::npos)
        << plain;
    const std::string full = kernelText(fullScene(), "forces.comp");
    EXPECT_NE(full.find("#define NUM_SPRING_OFFSETS 12\n"), std::string::npos);
    EXPECT_NE(full.find("ivec4(0, -2, 2, 11)"), std::string::npos);
    // One loop, whatever the families: the kernel text has a single spring loop.
    const std::regex loop(R"(for \(int o = 0; o < NUM_SPRING_OFFSETS; \+\+o\))");
    EXPECT_EQ(std::distance(std::sregex_iterator(full.begin(), full.end(), loop), {}), 1);
}

// Code that only one integrator has (docs/integrators.md), as it appears in the kernel text.
struct IntegratorCode {
    Method method;
    std::vector<const char*> markers;
};
const IntegratorCode kIntegratorCode[] = {
    {Method::ExplicitEuler, {"INTEGRATOR_EXPLICIT_EULER", "p += dt * v;\n    v += dt * a;"}},
    {Method::SymplecticEuler, {"INTEGRATOR_SYMPLECTIC_EULER", "v += dt * acceleration("}},
    {Method::Verlet, {"INTEGRATOR_VERLET", "kickAndDrift(", "vec3 kick("}},
    {Method::Rk4, {"INTEGRATOR_RK4", "rk4StartPositions", "rk4SumVelocities"}},
    {Method::ImplicitEuler,
     {"INTEGRATOR_IMPLICIT_EULER", "springJacobianTimes(", "stiffnessProduct(", "cgResidual",
      "groupSums"}},
};

std::string kernelsOfScene(Method method) {
    Scene scene = fullScene();
    scene.integrator.method = method;
    std::string text;
    for (Kernel k : kernelsOf(method))
        text += assembleKernel(kShaderDir, kernelFile(k), scene, {}).text;
    return std::regex_replace(text, std::regex("//[^\n]*"), "");
}

// The scene's integrator decides which kernels exist and what is in them: its own code, none of
// another integrator's.
TEST(GpuSpecialisation, OnlyTheScenesIntegratorIsInItsKernels) {
    for (const IntegratorCode& own : kIntegratorCode) {
        const std::string text = kernelsOfScene(own.method);
        for (const IntegratorCode& other : kIntegratorCode)
            for (const char* marker : other.markers)
                EXPECT_EQ(text.find(marker) != std::string::npos, other.method == own.method)
                    << methodName(own.method) << "'s kernels and '" << marker << "'";
    }
}

TEST(GpuSpecialisation, VariantLineNamesTheDefines) {
    EXPECT_EQ(describeGpuVariant(plainScene()),
              "HAS_STRUCTURAL NUM_PLANES=0 NUM_SPHERES=0 INTEGRATOR_EXPLICIT_EULER WX=16 WY=16 "
              "NUM_SPRING_OFFSETS=4");
    const std::string full = describeGpuVariant(fullScene());
    EXPECT_NE(full.find("HAS_WIND"), std::string::npos) << full;
    EXPECT_NE(full.find("NUM_PLANES=1 NUM_SPHERES=1"), std::string::npos) << full;
}

// Lines keep their numbers through includes and dropped blocks: the #line directives the
// loader writes encode file and line, and a compiler message maps back to both.
TEST(GpuShaderLoader, LogLinesMapBackToFileAndLine) {
    const ShaderSource s =
        assembleShader(kShaderDir, "compute/forces.comp", gpuDefines(plainScene(), {}));
    ASSERT_GE(s.files.size(), 3u);
    EXPECT_NE(s.files[1].find("forces.comp"), std::string::npos);
    EXPECT_EQ(mapShaderLog("0:20007(3): error: `y' undeclared", s.files),
              s.files[2] + ":7(3): error: `y' undeclared\n");  // Mesa
    EXPECT_EQ(mapShaderLog("1(12) : error C0000: syntax error", s.files),
              s.files[1] + ":12 : error C0000: syntax error\n");  // NVIDIA
    EXPECT_EQ(mapShaderLog("ERROR: 0:3: 'x' : undeclared", s.files),
              "ERROR: " + s.files[0] + ":3: 'x' : undeclared\n");  // AMD
}

class GpuCompiles : public GpuTest {};

// Every combination of spring families compiles and runs one step.
TEST_F(GpuCompiles, EveryFamilySubsetCompiles) {
    for (int mask = 0; mask < 8; ++mask) {
        Scene scene = plainScene();
        scene.springs = {mask & 1 ? 100.0 : 0.0, mask & 2 ? 50.0 : 0.0, mask & 4 ? 10.0 : 0.0};
        std::unique_ptr<Solver> solver = makeGpuSolver(scene);
        EXPECT_FALSE(solver->step(1).unstable) << mask;
    }
}

// Every integrator with every feature (wind, both colliders, pins) compiles and takes steps.
TEST_F(GpuCompiles, EveryIntegratorCompilesWithEveryFeature) {
    for (Method m : kMethods) {
        Scene scene = fullScene();
        scene.integrator.method = m;
        std::unique_ptr<Solver> solver = makeGpuSolver(scene);
        EXPECT_FALSE(solver->step(3).unstable) << methodName(m);
    }
}

// A scene allocates its integrator's buffers only: RK4 adds four vec4 per vertex (start and
// sums), implicit Euler four (Δv, r, p, A p), with colliders three more (the contacts in the
// solve), and one float per work group plus the solve's scalars; the Euler schemes and Verlet
// nothing beyond the state.
TEST_F(GpuCompiles, OnlyTheScenesIntegratorAllocatesBuffers) {
    Scene scene = fullScene();  // 8×5: one 16×16 work group
    const std::size_t vertexBuffer = 8 * 5 * sizeof(glm::vec4);
    auto bytes = [&](Method m) {
        scene.integrator.method = m;
        return GpuSolver(scene, {}).bufferBytes();
    };
    const std::size_t base = bytes(Method::ExplicitEuler);
    EXPECT_EQ(bytes(Method::SymplecticEuler), base);
    EXPECT_EQ(bytes(Method::Verlet), base);
    EXPECT_EQ(bytes(Method::Rk4), base + 4 * vertexBuffer);
    // Δv, r, p, A p and the contacts' three (the scene has colliders); two partial sums of the one
    // work group in a vec4; the solve's state; and for the block-Jacobi preconditioner its inverted
    // blocks, two vec4 per vertex.
    ASSERT_FALSE(scene.colliders.empty());
    const std::size_t cg = base + 7 * vertexBuffer + sizeof(glm::vec4) + sizeof(gpu::CgState);
    EXPECT_EQ(bytes(Method::ImplicitEuler), cg + 2 * vertexBuffer);  // jacobi, the default
    scene.integrator.preconditioner = Preconditioner::None;
    EXPECT_EQ(bytes(Method::ImplicitEuler), cg);
}

}  // namespace
}  // namespace cloth::test
