#pragma once
// The GL renderer: owns the shader programs, shadow maps and per-scene GPU caches, and runs the passes
// a RenderTarget asks for (shadow -> G-buffer -> lighting -> tone mapping). One Renderer per GlContext;
// destroy it (and its RenderTargets) before the context.

#include <cstdint>
#include <map>
#include <memory>

#include "core/render/camera.h"
#include "core/render/gl_context.h"
#include "core/render/modality.h"
#include "core/render/scene.h"

namespace sp::render {

class Framebuffers;
class GpuSceneCache;
class ShaderProgram;
class ShadowMaps;

// How often each pass ran (tests use it to check that only the needed passes run).
struct RenderStats {
    std::uint64_t frames = 0;
    std::uint64_t shadowPasses = 0; // one per shadow map rendered
    std::uint64_t gbufferPasses = 0;
    std::uint64_t lightingPasses = 0;
    std::uint64_t tonemapPasses = 0;
    std::uint64_t readbacks = 0; // one per modality read back
    std::uint64_t meshUploads = 0;
    std::uint64_t textureUploads = 0;
};

class Renderer {
  public:
    // Makes `context` current and compiles the programs; throws sp::InvalidState when a shader fails.
    explicit Renderer(const GlContext& context);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const ContextReport& contextReport() const { return context_.report(); }
    const RenderStats& stats() const;
    void resetStats();
    // Frees the GPU copies of a scene's meshes and textures (call when a Scene is destroyed).
    void releaseScene(const Scene& scene);

    // Runs the passes into `framebuffers` (used by RenderTarget; see render_target.h for the public way).
    void render(const Scene& scene, const Camera& camera, const PassSet& passes, Framebuffers& framebuffers);
    void countReadback() { ++stats_.readbacks; }

  private:
    GpuSceneCache& cacheFor(const Scene& scene);
    void geometryPass(const Scene& scene, const Camera& camera, GpuSceneCache& cache, Framebuffers& fb);
    void lightingPass(const Scene& scene, const Camera& camera, bool shadows, GpuSceneCache& cache,
                      Framebuffers& fb);
    void tonemapPass(const Camera& camera, Framebuffers& fb);

    const GlContext& context_;
    std::unique_ptr<ShaderProgram> geometry_;
    std::unique_ptr<ShaderProgram> shadow_;
    std::unique_ptr<ShaderProgram> lighting_;
    std::unique_ptr<ShaderProgram> tonemap_;
    std::unique_ptr<ShadowMaps> shadowMaps_;
    std::map<std::uint64_t, std::unique_ptr<GpuSceneCache>> caches_;
    unsigned emptyVao_ = 0;
    mutable RenderStats stats_;
};

} // namespace sp::render
