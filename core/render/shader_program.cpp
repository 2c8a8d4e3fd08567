#include "core/render/shader_program.h"

#include <epoxy/gl.h>

#include "core/base/error.h"

namespace sp::render {
namespace {

const char* stageName(GLenum stage) {
    return stage == GL_VERTEX_SHADER ? "vertex" : stage == GL_FRAGMENT_SHADER ? "fragment" : "compute";
}

GLuint compile(const std::string& name, GLenum stage, const char* source) {
    GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        glDeleteShader(shader);
        SP_THROW(InvalidState, "ShaderProgram::ShaderProgram(): ", stageName(stage), " shader of '", name,
                 "' does not compile: ", log);
    }
    return shader;
}

} // namespace

ShaderProgram::ShaderProgram(const std::string& name, const char* vertexSource, const char* fragmentSource)
    : name_(name) {
    GLuint vs = compile(name, GL_VERTEX_SHADER, vertexSource);
    GLuint fs = 0;
    try {
        fs = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    link({vs, fs});
}

ShaderProgram::ShaderProgram(const std::string& name, const char* computeSource) : name_(name) {
    link({compile(name, GL_COMPUTE_SHADER, computeSource)});
}

void ShaderProgram::link(std::initializer_list<unsigned> shaders) {
    program_ = glCreateProgram();
    for (unsigned shader : shaders)
        glAttachShader(program_, shader);
    glLinkProgram(program_);
    for (unsigned shader : shaders)
        glDeleteShader(shader);
    GLint ok = 0;
    glGetProgramiv(program_, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(program_, sizeof log, nullptr, log);
        glDeleteProgram(program_);
        SP_THROW(InvalidState, "ShaderProgram::ShaderProgram(): program '", name_, "' does not link: ", log);
    }
}

ShaderProgram::~ShaderProgram() {
    glDeleteProgram(program_);
}

void ShaderProgram::use() const {
    glUseProgram(program_);
}

int ShaderProgram::location(const std::string& uniform) {
    auto it = locations_.find(uniform);
    if (it != locations_.end())
        return it->second;
    int location = glGetUniformLocation(program_, uniform.c_str());
    locations_.emplace(uniform, location);
    return location;
}

void ShaderProgram::set(const std::string& u, int v) {
    glProgramUniform1i(program_, location(u), v);
}
void ShaderProgram::set(const std::string& u, unsigned v) {
    glProgramUniform1ui(program_, location(u), v);
}
void ShaderProgram::set(const std::string& u, float v) {
    glProgramUniform1f(program_, location(u), v);
}
void ShaderProgram::set(const std::string& u, const Eigen::Vector2f& v) {
    glProgramUniform2fv(program_, location(u), 1, v.data());
}
void ShaderProgram::set(const std::string& u, const Eigen::Vector3f& v) {
    glProgramUniform3fv(program_, location(u), 1, v.data());
}
void ShaderProgram::set(const std::string& u, const Eigen::Vector4f& v) {
    glProgramUniform4fv(program_, location(u), 1, v.data());
}
// Eigen is column-major like GL, so no transpose.
void ShaderProgram::set(const std::string& u, const Eigen::Matrix3f& v) {
    glProgramUniformMatrix3fv(program_, location(u), 1, GL_FALSE, v.data());
}
void ShaderProgram::set(const std::string& u, const Eigen::Matrix4f& v) {
    glProgramUniformMatrix4fv(program_, location(u), 1, GL_FALSE, v.data());
}

} // namespace sp::render
