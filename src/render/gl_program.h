// A vertex + fragment program from shaders/render/, assembled by the compute loader (so
// `#include` and mapped error logs work the same) and compiled in the current context.
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "gpu/shader_loader.h"

namespace cloth::render {

class GlProgram {
public:
    GlProgram() = default;
    // `vertex` and `fragment` are paths under the shader directory, e.g. "render/cloth.vert".
    // Throws std::runtime_error with the mapped compile or link log.
    GlProgram(const std::string& vertex, const std::string& fragment, const Defines& defines = {});
    ~GlProgram();
    GlProgram(GlProgram&& other) noexcept;
    GlProgram& operator=(GlProgram&& other) noexcept;
    GlProgram(const GlProgram&) = delete;
    GlProgram& operator=(const GlProgram&) = delete;

    void use() const;
    unsigned id() const { return id_; }

    // Uniform setters for the bound program; an unknown name (optimised away) is ignored.
    void set(const char* name, int v) const;
    void set(const char* name, float v) const;
    void set(const char* name, const glm::vec2& v) const;
    void set(const char* name, const glm::ivec2& v) const;
    void set(const char* name, const glm::vec3& v) const;
    void set(const char* name, const glm::vec4& v) const;
    void set(const char* name, const glm::mat4& m) const;

private:
    int location(const char* name) const;
    unsigned id_ = 0;
};

}  // namespace cloth::render
