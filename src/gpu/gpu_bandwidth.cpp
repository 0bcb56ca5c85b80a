#include "gpu/gpu_bandwidth.h"

#include <GL/glew.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "gpu/egl_context.h"
#include "gpu/shader_loader.h"

namespace cloth {
namespace {

constexpr int kLocalSize = 256;

// dst[k] = src[k] over a 2-D dispatch (a 1-D one would pass the 65535-group limit for large
// buffers); the row width is passed as a uniform.
constexpr const char* kCopyKernel = R"(#version 430
layout(local_size_x = 256) in;
layout(std430, binding = 0) readonly buffer Src { vec4 src[]; };
layout(std430, binding = 1) writeonly buffer Dst { vec4 dst[]; };
uniform uint count;
uniform uint rowGroups;
void main() {
    uint k = (gl_WorkGroupID.y * rowGroups + gl_WorkGroupID.x) * 256u + gl_LocalInvocationID.x;
    if (k < count) dst[k] = src[k];
}
)";

}  // namespace

double measureGpuCopyBandwidth(std::size_t bytes, int repeats) {
    GlContext::instance().makeCurrent();
    const std::size_t count = bytes / 16;
    const unsigned program = compileComputeProgram({"copy kernel", kCopyKernel, {"copy kernel"}});
    unsigned buffers[2] = {};
    glGenBuffers(2, buffers);
    for (unsigned b : buffers) {
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, b);
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(count * 16), nullptr, GL_DYNAMIC_COPY);
        glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, nullptr);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    glUseProgram(program);
    const std::size_t groups = (count + kLocalSize - 1) / kLocalSize;
    const unsigned rowGroups = unsigned(std::min<std::size_t>(groups, 65535));
    const unsigned rows = unsigned((groups + rowGroups - 1) / rowGroups);
    glUniform1ui(glGetUniformLocation(program, "count"), unsigned(count));
    glUniform1ui(glGetUniformLocation(program, "rowGroups"), rowGroups);
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= repeats; ++r) {  // r = 0 is the warm-up
        glFinish();
        const auto t0 = std::chrono::steady_clock::now();
        glDispatchCompute(rowGroups, rows, 1);
        glFinish();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (r > 0) best = std::min(best, s);
    }
    glDeleteBuffers(2, buffers);
    glDeleteProgram(program);
    return 2.0 * double(count * 16) / best;
}

}  // namespace cloth
