#pragma once
// The off-screen targets of one RenderTarget: one texture per Target a frame writes, a depth buffer, and
// the framebuffers of the surface and attribute passes, each attaching its targets in Target order and
// both the one depth buffer (the attribute pass tests against the surface pass's depth).
// Textures are allocated only for the targets the passes write and kept across frames while the size
// and format fit. With layers, every texture is an array of that many layers and the framebuffers are
// layered: each view drawn into them picks its layer (gl_Layer), as the views sharing a page of
// FramebufferAtlas do. With multisampling (PassSet::samples > 1; never layered), the shaded targets also
// have multisampled copies, drawn by the surface pass and resolved into them. With spatial samples
// (PassSet::spatialSamples > 1; never layered), they have framebuffers of their own that each sample's pass
// draws (spatialSampleSurface()), and arrays of a layer a sample that each pass is copied into and that are
// averaged into them. Needs a current context.

#include <array>
#include <memory>

#include "core/render/modality.h"

namespace sp::render {

class Framebuffers {
  public:
    Framebuffers() = default;
    ~Framebuffers();
    Framebuffers(const Framebuffers&) = delete;
    Framebuffers& operator=(const Framebuffers&) = delete;

    // (Re)allocates what `passes` writes at width x height (in `layers` layers; 0: plain 2D textures); keeps
    // the textures that already fit.
    void ensure(int width, int height, const PassSet& passes, int layers = 0);
    // The texture of a target, 0 when the last ensure() did not ask for it.
    unsigned texture(Target target) const { return textures_[static_cast<std::size_t>(target)]; }
    // The depth texture of the surface pass (with layers, an array), 0 before one was drawn.
    unsigned depthTexture() const { return depthBuffer_; }
    // Where a target can be read: the framebuffer that attaches it and the attachment index.
    struct Attachment {
        unsigned fbo = 0;
        int index = -1;
    };
    Attachment attachment(Target target) const;
    // Where a target's layer can be read (layered framebuffers): a framebuffer of its own with that layer
    // attached, since reading a layered one reads its first layer.
    Attachment layerAttachment(Target target, int layer);

    // The multisampled texture of a shaded target (PassSet::samples > 1), 0 when there is none.
    unsigned multisampleTexture(Target target) const {
        return multisampled_[static_cast<std::size_t>(target)];
    }

    int width = 0;
    int height = 0;
    int layers = 0; // 0: plain 2D textures
    unsigned surfaceFbo = 0;
    unsigned attributeFbo = 0;
    // With PassSet::samples > 1: the multisampled framebuffer the surface pass draws in (its targets' and a
    // depth buffer's multisampled copies, attached as surfaceFbo attaches the targets), and its samples.
    unsigned multisampleFbo = 0;
    int samples = 1;

    // With PassSet::spatialSamples > 1: the framebuffers one spatial sample's pass draws the shaded targets
    // in (see spatialSampleSurface()), else null; and the array of a shaded target's samples, a layer each
    // (copied by copySample()), else 0.
    Framebuffers* spatialSampled() const { return spatialSampled_.get(); }
    unsigned sampleLayers(Target target) const { return sampleLayers_[static_cast<std::size_t>(target)]; }
    // Copies what spatialSampled() holds of every shaded target into layer `sample` of sampleLayers().
    void copySample(int sample) const;

  private:
    void release();
    void releaseMultisampled();
    void ensureMultisampled(const PassSet& passes);
    unsigned makeFramebuffer(TargetMask targets, bool depth, const char* what);

    std::array<unsigned, kTargetCount> textures_{};
    std::array<unsigned, kTargetCount> formats_{};
    unsigned depthBuffer_ = 0; // a depth texture (with layers, an array)
    unsigned readFbo_ = 0;     // layerAttachment()'s
    std::array<unsigned, kTargetCount> multisampled_{};
    unsigned multisampledDepth_ = 0;
    TargetMask multisampledTargets_ = 0;
    TargetMask surfaceTargets_ = 0;
    TargetMask attributeTargets_ = 0;
    void releaseSampleLayers();
    std::unique_ptr<Framebuffers> spatialSampled_;
    std::array<unsigned, kTargetCount> sampleLayers_{};
    TargetMask sampledTargets_ = 0;
    int sampleCount_ = 0;
};

} // namespace sp::render
