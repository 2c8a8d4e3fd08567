#include "core/render/framebuffers.h"

#include <epoxy/gl.h>

#include "core/base/error.h"

namespace sp::render {
namespace {

GLenum formatOf(Target target, bool compact) {
    if (compact && target == Target::Normal)
        return GL_RG32F;
    if (compact && (kHalfTargets & targetBit(target)) != 0)
        return GL_RGBA16UI;
    switch (target) {
    case Target::Position:
    case Target::Normal:
        return GL_RGBA32F;
    case Target::Depth:
        return GL_R32F;
    case Target::Ids:
    case Target::GBufferMaterial:
        return GL_RG32UI; // never filtered or blended
    case Target::GBuffer:
    case Target::Record:
        return GL_R32UI;
    case Target::FinalColor:
        return GL_RGBA8;
    default:
        return GL_RGBA16F;
    }
}

GLuint makeTexture(GLenum format, int width, int height, int layers) {
    GLuint texture = 0;
    if (layers > 0) {
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
        glTextureStorage3D(texture, 1, format, width, height, layers);
    } else {
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, format, width, height);
    }
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

int indexIn(TargetMask targets, Target target) {
    const TargetMask bit = targetBit(target);
    if ((targets & bit) == 0)
        return -1;
    return __builtin_popcount(targets & (bit - 1));
}

} // namespace

Framebuffers::~Framebuffers() {
    release();
}

void Framebuffers::releaseMultisampled() {
    if (multisampleFbo == 0 && multisampledDepth_ == 0)
        return;
    glDeleteFramebuffers(1, &multisampleFbo);
    glDeleteTextures(GLsizei(multisampled_.size()), multisampled_.data());
    glDeleteTextures(1, &multisampledDepth_);
    multisampleFbo = multisampledDepth_ = 0;
    multisampled_.fill(0);
    multisampledTargets_ = 0;
    samples = 1;
}

void Framebuffers::releaseSampleLayers() {
    spatialSampled_.reset();
    if (sampledTargets_ == 0)
        return;
    glDeleteTextures(GLsizei(sampleLayers_.size()), sampleLayers_.data());
    sampleLayers_.fill(0);
    sampledTargets_ = 0;
    sampleCount_ = 0;
}

void Framebuffers::copySample(int sample) const {
    for (std::size_t t = 0; t < kTargetCount; ++t)
        if ((sampledTargets_ & (TargetMask(1) << t)) != 0)
            glCopyImageSubData(spatialSampled_->texture(static_cast<Target>(t)), GL_TEXTURE_2D, 0, 0, 0, 0,
                               sampleLayers_[t], GL_TEXTURE_2D_ARRAY, 0, 0, 0, sample, width, height, 1);
}

void Framebuffers::release() {
    releaseMultisampled();
    releaseSampleLayers();
    if (surfaceFbo == 0 && attributeFbo == 0 && depthBuffer_ == 0)
        return; // nothing allocated: no GL call, so a never-used target needs no context
    glDeleteFramebuffers(1, &surfaceFbo);
    glDeleteFramebuffers(1, &attributeFbo);
    glDeleteFramebuffers(1, &readFbo_);
    readFbo_ = 0;
    glDeleteTextures(GLsizei(textures_.size()), textures_.data());
    glDeleteTextures(1, &depthBuffer_);
    surfaceFbo = attributeFbo = depthBuffer_ = 0;
    textures_.fill(0);
    formats_.fill(0);
    surfaceTargets_ = attributeTargets_ = 0;
    width = height = layers = 0;
}

unsigned Framebuffers::makeFramebuffer(TargetMask targets, bool depth, const char* what) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    GLenum drawBuffers[kTargetCount];
    int count = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((targets & (TargetMask(1) << t)) == 0)
            continue;
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + count, textures_[t], 0);
        drawBuffers[count] = GL_COLOR_ATTACHMENT0 + count;
        ++count;
    }
    glNamedFramebufferDrawBuffers(fbo, count, drawBuffers);
    if (depth) // with layers, every layer: a layered framebuffer
        glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depthBuffer_, 0);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    SP_CHECK(status == GL_FRAMEBUFFER_COMPLETE, InvalidState, "Framebuffers::ensure(): the ", what,
             " framebuffer is incomplete (status 0x", std::hex, status, ")");
    return fbo;
}

void Framebuffers::ensure(int w, int h, const PassSet& passes, int layerCount) {
    if (w != width || h != height || layerCount != layers)
        release();
    width = w;
    height = h;
    layers = layerCount;
    const TargetMask needed = passes.surfaceTargets | passes.attributeTargets;
    bool changed = passes.surfaceTargets != surfaceTargets_ || passes.attributeTargets != attributeTargets_;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((needed & (TargetMask(1) << t)) == 0)
            continue; // kept for when the modalities come back; freed with the size
        const GLenum format = formatOf(static_cast<Target>(t), passes.compactTargets);
        if (textures_[t] != 0 && formats_[t] == format)
            continue;
        glDeleteTextures(1, &textures_[t]);
        textures_[t] = makeTexture(format, w, h, layers);
        formats_[t] = format;
        changed = true;
    }
    if (passes.surface && depthBuffer_ == 0) {
        // A texture, which the compute lighting pass reads (PassSet::computeLighting()); with layers, an
        // array.
        depthBuffer_ = makeTexture(GL_DEPTH_COMPONENT32F, w, h, layers);
        changed = true;
    }
    if (passes.spatialSamples > 1) {
        SP_CHECK(layers == 0, InvalidArgument,
                 "Framebuffers::ensure(): spatially sampled targets cannot be layered");
        if (sampledTargets_ != passes.surfaceTargets || sampleCount_ != passes.spatialSamples) {
            releaseSampleLayers();
            for (std::size_t t = 0; t < kTargetCount; ++t)
                if ((passes.surfaceTargets & (TargetMask(1) << t)) != 0)
                    sampleLayers_[t] =
                        makeTexture(formatOf(static_cast<Target>(t), false), w, h, passes.spatialSamples);
            sampledTargets_ = passes.surfaceTargets;
            sampleCount_ = passes.spatialSamples;
        }
        if (!spatialSampled_)
            spatialSampled_ = std::make_unique<Framebuffers>();
        spatialSampled_->ensure(w, h, spatialSampleSurface(passes));
    } else {
        releaseSampleLayers();
    }
    ensureMultisampled(passes);
    if (!changed)
        return;
    glDeleteFramebuffers(1, &surfaceFbo);
    glDeleteFramebuffers(1, &attributeFbo);
    surfaceFbo = attributeFbo = 0;
    surfaceTargets_ = passes.surfaceTargets;
    attributeTargets_ = passes.attributeTargets;
    if (surfaceTargets_ != 0)
        surfaceFbo = makeFramebuffer(surfaceTargets_, true, "surface");
    if (attributeTargets_ != 0)
        attributeFbo = makeFramebuffer(attributeTargets_, true, "attribute");
}

void Framebuffers::ensureMultisampled(const PassSet& passes) {
    if (passes.samples <= 1) {
        releaseMultisampled();
        return;
    }
    SP_CHECK(layers == 0, InvalidArgument, "Framebuffers::ensure(): multisampled targets cannot be layered");
    if (multisampleFbo != 0 && samples == passes.samples && multisampledTargets_ == passes.surfaceTargets)
        return;
    releaseMultisampled();
    const auto make = [&](GLenum format) {
        GLuint texture = 0;
        glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &texture);
        // Fixed sample locations: every pixel's samples sit alike, so a resolve weighs them alike.
        glTextureStorage2DMultisample(texture, passes.samples, format, width, height, GL_TRUE);
        return texture;
    };
    glCreateFramebuffers(1, &multisampleFbo);
    GLenum drawBuffers[kTargetCount];
    int count = 0;
    for (std::size_t t = 0; t < kTargetCount; ++t) {
        if ((passes.surfaceTargets & (TargetMask(1) << t)) == 0)
            continue;
        multisampled_[t] = make(formatOf(static_cast<Target>(t), false));
        glNamedFramebufferTexture(multisampleFbo, GL_COLOR_ATTACHMENT0 + count, multisampled_[t], 0);
        drawBuffers[count] = GL_COLOR_ATTACHMENT0 + count;
        ++count;
    }
    glNamedFramebufferDrawBuffers(multisampleFbo, count, drawBuffers);
    multisampledDepth_ = make(GL_DEPTH_COMPONENT32F);
    glNamedFramebufferTexture(multisampleFbo, GL_DEPTH_ATTACHMENT, multisampledDepth_, 0);
    const GLenum status = glCheckNamedFramebufferStatus(multisampleFbo, GL_FRAMEBUFFER);
    SP_CHECK(status == GL_FRAMEBUFFER_COMPLETE, InvalidState, "Framebuffers::ensure(): the ", passes.samples,
             "-sample framebuffer is incomplete (status 0x", std::hex, status, ")");
    samples = passes.samples;
    multisampledTargets_ = passes.surfaceTargets;
}

Framebuffers::Attachment Framebuffers::layerAttachment(Target target, int layer) {
    const unsigned texture = textures_[static_cast<std::size_t>(target)];
    SP_CHECK(layers > 0 && layer >= 0 && layer < layers && texture != 0, InvalidState,
             "Framebuffers::layerAttachment(): no layer ", layer, " of target ", targetName(target), " in ",
             layers, " layers");
    if (readFbo_ == 0)
        glCreateFramebuffers(1, &readFbo_);
    glNamedFramebufferTextureLayer(readFbo_, GL_COLOR_ATTACHMENT0, texture, 0, layer);
    return {readFbo_, 0};
}

Framebuffers::Attachment Framebuffers::attachment(Target target) const {
    if (int index = indexIn(surfaceTargets_, target); index >= 0)
        return {surfaceFbo, index};
    if (int index = indexIn(attributeTargets_, target); index >= 0)
        return {attributeFbo, index};
    SP_THROW(InvalidState, "Framebuffers::attachment(): target ", targetName(target),
             " was not rendered in the last frame");
}

} // namespace sp::render
