// Small helpers over GL shader storage buffers of vec4s, shared by GpuSolver's files. Need the
// solver's context current.
#pragma once

#include <GL/glew.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace cloth::gpu {

inline constexpr std::size_t kVec4 = sizeof(glm::vec4);  // one element per vertex or pin

// (Re)allocates `buffer` to `bytes` and fills it with `data`, or zeros when `data` is null.
inline void bufferData(unsigned buffer, const void* data, std::size_t bytes) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    // An empty table still gets a vec4: a zero-sized binding is an error in GL.
    const std::size_t size = std::max(bytes, kVec4);
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(size), nullptr, GL_DYNAMIC_COPY);
    if (data != nullptr && bytes > 0)
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes), data);
    else
        glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, nullptr);
}

template <typename T>
void bufferData(unsigned buffer, const std::vector<T>& v) {
    bufferData(buffer, v.data(), v.size() * sizeof(T));
}

// Overwrites part of an allocated buffer. After a dispatch that wrote it, the caller first
// issues glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT); so before the reads below.
inline void subData(unsigned buffer, std::size_t offset, const void* data, std::size_t bytes) {
    if (bytes == 0) return;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(offset), GLsizeiptr(bytes), data);
}

inline std::vector<glm::vec4> downloadVec4(unsigned buffer, std::size_t count) {
    std::vector<glm::vec4> out(count);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(count * kVec4), out.data());
    return out;
}

// Element k alone (16 bytes).
inline glm::vec4 readElement(unsigned buffer, std::int64_t k) {
    glm::vec4 out(0);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(std::size_t(k) * kVec4), kVec4, &out);
    return out;
}

// Double to float exactly as the CPU float backend converts (glm's per-component cast).
inline glm::vec4 vec4(const glm::dvec3& v, double w) {
    return glm::vec4(glm::vec3(v), float(w));
}

}  // namespace cloth::gpu
