#pragma once
// The off-screen render targets of one RenderTarget: G-buffer, lighting and tone-mapping framebuffers,
// allocated only for the passes that run. Needs a current context.

#include "core/render/modality.h"
#include "core/render/shaders.h"

namespace sp::render {

class Framebuffers {
  public:
    Framebuffers() = default;
    ~Framebuffers();
    Framebuffers(const Framebuffers&) = delete;
    Framebuffers& operator=(const Framebuffers&) = delete;

    // (Re)allocates the framebuffers `passes` needs at width x height; keeps what already fits.
    void ensure(int width, int height, const PassSet& passes);

    int width = 0;
    int height = 0;
    unsigned gbufferFbo = 0;
    unsigned gbufferTextures[shaders::GBufferTargetCount] = {};
    unsigned depthBuffer = 0;
    unsigned lightingFbo = 0;
    unsigned lightingTextures[shaders::LightingTargetCount] = {};
    unsigned tonemapFbo = 0;
    unsigned tonemapTexture = 0;

  private:
    void release();
};

} // namespace sp::render
