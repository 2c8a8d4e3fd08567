#pragma once
// Instanced drawing: what each drawn instance gives the surface and shadow programs, as instanced vertex
// attributes read once per instance. One draw call then renders every instance of a mesh that shares a
// program and textures, instead of one call (and a dozen uniform updates) per instance: a driver's cost
// per call, a software rasteriser's most of all (state validation, constants copied into each draw), grew
// with the number of objects in view.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace sp::render {

// The vertex array binding the records are read from (a mesh's own attributes use bindings 0-2).
inline constexpr unsigned kInstanceBinding = 3;
// The attribute locations of a record's fields (a mesh's own attributes use locations 0-2); GLSL's are
// declared from these (shaders.cpp). A mat4 takes four consecutive locations, one column each.
inline constexpr unsigned kInstanceModelViewProjection = 3;
inline constexpr unsigned kInstanceModelRows = 7; // three locations
inline constexpr unsigned kInstanceDepthRow = 10;
inline constexpr unsigned kInstanceBaseColor = 11;
inline constexpr unsigned kInstanceMaterial = 12;
inline constexpr unsigned kInstanceEmissive = 13;
inline constexpr unsigned kInstanceIds = 14;

// One drawn instance (a submesh of an instance, for the surface passes). Matrices are composed in double
// precision on the CPU and rounded once, as the uniforms they replace were.
struct InstanceRecord {
    float modelViewProjection[16]; // column-major mesh -> clip; light clip for a shadow map
    float modelRows[12];           // rows 0-2 of mesh -> world
    float depthRow[4];             // row 0 of mesh -> camera: the distance along the optical axis
    float baseColor[4];            // rgba factor
    float material[4];             // roughness, metallic, ambient occlusion, 1 / textureSize (0: mesh uvs)
    float emissive[4];             // rgb, the level of detail's shadow slack (Renderer::Draw::shadowSlack)
    std::uint32_t ids[4];          // object id, material id, the record's index (Target::GBuffer), 0

    void setModelViewProjection(const Eigen::Matrix4d& matrix);
    void setModel(const Eigen::Matrix4d& model, const Eigen::Matrix4d& modelToCamera);
};
static_assert(sizeof(InstanceRecord) == 192, "records are tightly packed vec4s");

// Declares `vao`'s instanced attributes (the record's fields at kInstance* locations, binding
// kInstanceBinding, one record per instance). Called once per vertex array.
void configureInstanceAttributes(unsigned vao);

// A stream of records for instanced draws. upload() replaces the contents with new storage, so that draws
// still queued on the previous records are not waited for; bind() points a configured vertex array at it.
class InstanceBuffer {
  public:
    InstanceBuffer();
    ~InstanceBuffer();
    InstanceBuffer(const InstanceBuffer&) = delete;
    InstanceBuffer& operator=(const InstanceBuffer&) = delete;

    void upload(const std::vector<InstanceRecord>& records);
    void bind(unsigned vao) const;
    // The buffer holding the records (from offset 0), which the compute lighting pass reads as storage.
    unsigned buffer() const { return buffer_; }

  private:
    unsigned buffer_ = 0;
};

} // namespace sp::render
