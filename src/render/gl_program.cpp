#include "render/gl_program.h"

#include <GL/glew.h>

#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <utility>

namespace cloth::render {
namespace {

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    return log.c_str();
}

GLuint compile(GLenum stage, const ShaderSource& source) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        const std::string log = mapShaderLog(shaderLog(shader), source.files);
        glDeleteShader(shader);
        throw std::runtime_error("compiling " + source.name + " failed:\n" + log);
    }
    return shader;
}

}  // namespace

GlProgram::GlProgram(const std::string& vertex, const std::string& fragment,
                     const Defines& defines) {
    const std::string dir = findShaderDirectory().path;
    const GLuint vs = compile(GL_VERTEX_SHADER, assembleShader(dir, vertex, defines));
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, assembleShader(dir, fragment, defines));
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    id_ = glCreateProgram();
    glAttachShader(id_, vs);
    glAttachShader(id_, fs);
    glLinkProgram(id_);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(id_, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(id_, length, nullptr, log.data());
        glDeleteProgram(id_);
        id_ = 0;
        throw std::runtime_error("linking " + vertex + " + " + fragment + " failed:\n" +
                                 log.c_str());
    }
}

GlProgram::~GlProgram() {
    if (id_ != 0) glDeleteProgram(id_);
}

GlProgram::GlProgram(GlProgram&& other) noexcept : id_(std::exchange(other.id_, 0)) {}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
    std::swap(id_, other.id_);
    return *this;
}

void GlProgram::use() const {
    glUseProgram(id_);
}

int GlProgram::location(const char* name) const {
    return glGetUniformLocation(id_, name);
}

void GlProgram::set(const char* name, int v) const {
    glUniform1i(location(name), v);
}
void GlProgram::set(const char* name, float v) const {
    glUniform1f(location(name), v);
}
void GlProgram::set(const char* name, const glm::vec2& v) const {
    glUniform2fv(location(name), 1, glm::value_ptr(v));
}
void GlProgram::set(const char* name, const glm::ivec2& v) const {
    glUniform2iv(location(name), 1, glm::value_ptr(v));
}
void GlProgram::set(const char* name, const glm::vec3& v) const {
    glUniform3fv(location(name), 1, glm::value_ptr(v));
}
void GlProgram::set(const char* name, const glm::vec4& v) const {
    glUniform4fv(location(name), 1, glm::value_ptr(v));
}
void GlProgram::set(const char* name, const glm::mat4& m) const {
    glUniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(m));
}

}  // namespace cloth::render
