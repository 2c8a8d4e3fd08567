#include "core/render/framebuffers.h"

#include <epoxy/gl.h>

#include "core/base/error.h"

namespace sp::render {
namespace {

GLuint makeTexture(GLenum format, int width, int height) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, width, height);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

GLuint makeFramebuffer(const GLuint* textures, int count, GLuint depth, const char* what) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    GLenum drawBuffers[8];
    for (int i = 0; i < count; ++i) {
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + i, textures[i], 0);
        drawBuffers[i] = GL_COLOR_ATTACHMENT0 + i;
    }
    glNamedFramebufferDrawBuffers(fbo, count, drawBuffers);
    if (depth != 0)
        glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    SP_CHECK(status == GL_FRAMEBUFFER_COMPLETE, InvalidState, "Framebuffers::ensure(): the ", what,
             " framebuffer is incomplete (status 0x", std::hex, status, ")");
    return fbo;
}

} // namespace

Framebuffers::~Framebuffers() {
    release();
}

void Framebuffers::release() {
    if (gbufferFbo == 0 && lightingFbo == 0 && tonemapFbo == 0)
        return; // nothing allocated: no GL call, so a never-used target needs no context
    glDeleteFramebuffers(1, &gbufferFbo);
    glDeleteTextures(shaders::GBufferTargetCount, gbufferTextures);
    glDeleteRenderbuffers(1, &depthBuffer);
    glDeleteFramebuffers(1, &lightingFbo);
    glDeleteTextures(shaders::LightingTargetCount, lightingTextures);
    glDeleteFramebuffers(1, &tonemapFbo);
    glDeleteTextures(1, &tonemapTexture);
    gbufferFbo = depthBuffer = lightingFbo = tonemapFbo = tonemapTexture = 0;
    for (unsigned& texture : gbufferTextures)
        texture = 0;
    for (unsigned& texture : lightingTextures)
        texture = 0;
    width = height = 0;
}

void Framebuffers::ensure(int w, int h, const PassSet& passes) {
    if (w != width || h != height)
        release();
    width = w;
    height = h;
    if (passes.gbuffer && gbufferFbo == 0) {
        // Float32 where the modality is float32 (position, normal, depth), float16 for material
        // attributes, and an integer target for the ids (never filtered or blended).
        const GLenum formats[shaders::GBufferTargetCount] = {GL_RGBA32F, GL_RGBA32F, GL_R32F,  GL_RGBA16F,
                                                             GL_RGBA16F, GL_RGBA16F, GL_RG32UI};
        for (int i = 0; i < shaders::GBufferTargetCount; ++i)
            gbufferTextures[i] = makeTexture(formats[i], w, h);
        glCreateRenderbuffers(1, &depthBuffer);
        glNamedRenderbufferStorage(depthBuffer, GL_DEPTH_COMPONENT32F, w, h);
        gbufferFbo = makeFramebuffer(gbufferTextures, shaders::GBufferTargetCount, depthBuffer, "G-buffer");
    }
    if (passes.lighting && lightingFbo == 0) {
        for (unsigned& texture : lightingTextures)
            texture = makeTexture(GL_RGBA16F, w, h);
        lightingFbo = makeFramebuffer(lightingTextures, shaders::LightingTargetCount, 0, "lighting");
    }
    if (passes.tonemap && tonemapFbo == 0) {
        tonemapTexture = makeTexture(GL_RGBA8, w, h);
        tonemapFbo = makeFramebuffer(&tonemapTexture, 1, 0, "tone-mapping");
    }
}

} // namespace sp::render
