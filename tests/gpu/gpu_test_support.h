// Shared by the GPU tests: open the headless context once, skip where none can be made (fail
// under CLOTH_REQUIRE_GPU=1, DESIGN.md §6), and run scenes on the GPU and the reference.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include "cpu/cpu_backend.h"
#include "gpu/egl_context.h"
#include "gpu/gpu_backend.h"
#include "reference/reference.h"
#include "scene/scene_loader.h"
#include "solver/solver.h"
#include "support/reference_bridge.h"

namespace cloth::test {

// Sets an environment variable for one scope and puts the old value back.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value, bool overwrite = true) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        if (overwrite || !old_) ::setenv(name, value, 1);
    }
    ~ScopedEnv() {
        if (old_)
            ::setenv(name_.c_str(), old_->c_str(), 1);
        else
            ::unsetenv(name_.c_str());
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    std::string name_;
    std::optional<std::string> old_;
};

// Empty when the context exists, else why not. Tried once per process.
inline const std::string& gpuUnavailableReason() {
    static const std::string reason = [] {
        try {
            GlContext::instance();
            return std::string();
        } catch (const std::exception& e) {
            return std::string(e.what()).empty() ? std::string("unknown") : std::string(e.what());
        }
    }();
    return reason;
}

inline bool gpuRequired() {
    const char* v = std::getenv("CLOTH_REQUIRE_GPU");
    return v != nullptr && std::string(v) == "1";
}

// The GPU library's shader folder set to `dir` for the scope (configureGpu), then back.
class ScopedShaderDir {
public:
    explicit ScopedShaderDir(const std::string& dir) : saved_(gpuSetup()) {
        GpuSetup s = saved_;
        s.shaderDir = dir;
        configureGpu(s);
    }
    ~ScopedShaderDir() { configureGpu(saved_); }
    ScopedShaderDir(const ScopedShaderDir&) = delete;
    ScopedShaderDir& operator=(const ScopedShaderDir&) = delete;

private:
    GpuSetup saved_;
};

// Tests of the working tree use its shaders/: the copy next to the executable is refreshed only
// when clothsim relinks.
class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
        if (!gpuUnavailableReason().empty()) {
            if (gpuRequired()) GTEST_FAIL() << "CLOTH_REQUIRE_GPU=1: " << gpuUnavailableReason();
            GTEST_SKIP() << "no GPU context: " << gpuUnavailableReason();
        }
    }
    ScopedShaderDir shaders_{CLOTH_SOURCE_DIR "/shaders"};
};

inline SimState runGpu(const Scene& scene, long steps, const GpuOptions& options = {}) {
    std::unique_ptr<Solver> solver = makeGpuSolver(scene, options);
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << scene.name << ": " << r.reason;
    EXPECT_EQ(r.stepsTaken, steps) << scene.name;
    return solver->read();
}

inline SimState runCpuFloat(const Scene& scene, long steps) {
    std::unique_ptr<Solver> solver = makeCpuSolver(scene, {Precision::Float, 1});
    const StepResult r = solver->step(steps);
    EXPECT_FALSE(r.unstable) << scene.name << ": " << r.reason;
    return solver->read();
}

inline ref::Simulation runReference(const Scene& scene, long steps) {
    ref::Simulation sim(toReference(scene));
    for (long s = 0; s < steps; ++s) sim.step();
    EXPECT_TRUE(sim.finiteAndBelowMaxSpeed()) << scene.name << ": the reference blew up";
    return sim;
}

// max_k |a_k − b_k| / extent.
inline double maxDifferenceOverExtent(const SimState& a, const SimState& b, double extent) {
    double worst = 0;
    for (std::size_t k = 0; k < a.positions.size(); ++k)
        worst = std::max(worst, glm::length(a.positions[k] - b.positions[k]));
    return worst / extent;
}

}  // namespace cloth::test
