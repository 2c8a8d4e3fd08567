#pragma once
// A linked GLSL program (vertex + fragment, or compute) with cached uniform locations. Needs a current
// context.

#include <initializer_list>
#include <string>
#include <unordered_map>

#include <Eigen/Core>

namespace sp::render {

class ShaderProgram {
  public:
    // Compiles and links; throws sp::InvalidState with the compiler log naming `name` on failure.
    ShaderProgram(const std::string& name, const char* vertexSource, const char* fragmentSource);
    // A compute program.
    ShaderProgram(const std::string& name, const char* computeSource);
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
    // Links the compiled `shaders` (deleting them) into program_.
    void link(std::initializer_list<unsigned> shaders);

    std::string name_;
    unsigned program_ = 0;
    std::unordered_map<std::string, int> locations_;
};

} // namespace sp::render
