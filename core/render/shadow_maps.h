#pragma once
// Shadow maps of directional and spot lights, one layer of a depth texture array each. Directional maps
// are orthographic and fit the scene's bounding sphere; spot maps are perspective over the cone.
// Point lights cast no shadows. Needs a current context.

#include <vector>

#include <Eigen/Core>

#include "core/render/gpu_scene_cache.h"
#include "core/render/scene.h"
#include "core/render/shader_program.h"

namespace sp::render {

struct ShadowInfo {
    int lightOrdinal = -1; // the light's position in the scene's light order
    int layer = -1;
    Eigen::Matrix4f worldToClip = Eigen::Matrix4f::Identity();
    float texel = 0.0f; // world size of a texel (per metre of distance when perspective)
    bool perspective = false;
};

class ShadowMaps {
  public:
    ShadowMaps() = default;
    ~ShadowMaps();
    ShadowMaps(const ShadowMaps&) = delete;
    ShadowMaps& operator=(const ShadowMaps&) = delete;

    // Brings the maps up to date for `scene`: one for each of the first shaders::kMaxShadowMaps
    // shadow-casting directional or spot lights (in handle order). Returns how many maps were rendered:
    // 0 when nothing that shapes them (lights, visible instances and their meshes, the resolution)
    // changed since the last call, so the views of one frame and still scenes share one render.
    std::size_t render(const Scene& scene, int resolution, GpuSceneCache& cache, ShaderProgram& depthProgram);
    // Where each map is, as of the last render().
    const std::vector<ShadowInfo>& infos() const { return infos_; }
    unsigned texture() const { return texture_; }

  private:
    void ensure(int resolution);
    unsigned texture_ = 0;
    unsigned fbo_ = 0;
    int resolution_ = 0;
    bool warnedTooMany_ = false;
    std::vector<ShadowInfo> infos_;
    std::vector<double> signature_; // what the maps were rendered from
};

} // namespace sp::render
