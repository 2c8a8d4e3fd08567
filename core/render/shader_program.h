#pragma once
// A linked GLSL program (vertex + fragment) with cached uniform locations. Needs a current context.

#include <string>
#include <unordered_map>

#include <Eigen/Core>

namespace sp::render {

class ShaderProgram {
  public:
    // Compiles and links; throws sp::InvalidState with the compiler log naming `name` on failure.
    ShaderProgram(const std::string& name, const char* vertexSource, const char* fragmentSource);
    ~ShaderProgram();
    ShaderProgram(const ShaderProgram&) = delete;
    ShaderProgram& operator=(const ShaderProgram&) = delete;

    void use() const;
    unsigned id() const { return program_; }
    // Location of a uniform, -1 when the linker removed it (setting it is then a no-op, as in GL).
    int location(const std::string& uniform);

    void set(const std::string& uniform, int value);
    void set(const std::string& uniform, unsigned value);
    void set(const std::string& uniform, float value);
    void set(const std::string& uniform, const Eigen::Vector2f& value);
    void set(const std::string& uniform, const Eigen::Vector3f& value);
    void set(const std::string& uniform, const Eigen::Vector4f& value);
    void set(const std::string& uniform, const Eigen::Matrix3f& value);
    void set(const std::string& uniform, const Eigen::Matrix4f& value);

  private:
    std::string name_;
    unsigned program_ = 0;
    std::unordered_map<std::string, int> locations_;
};

} // namespace sp::render
