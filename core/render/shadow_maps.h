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
    LightId light;
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

    // Renders a map for each of the first shaders::kMaxShadowMaps shadow-casting directional or spot
    // lights (in handle order) and returns where each one is.
    std::vector<ShadowInfo> render(const Scene& scene, int resolution, GpuSceneCache& cache,
                                   ShaderProgram& depthProgram);
    unsigned texture() const { return texture_; }

  private:
    void ensure(int resolution);
    unsigned texture_ = 0;
    unsigned fbo_ = 0;
    int resolution_ = 0;
    bool warnedTooMany_ = false;
};

} // namespace sp::render
