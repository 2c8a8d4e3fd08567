#include "core/render/screen_occlusion.h"

#include <epoxy/gl.h>

#include "core/base/error.h"
#include "core/render/shader_program.h"

namespace sp::render {
namespace {

// Read and written as images only (image loads and framebuffer stores), so no sampler state.
GLuint makeTexture(GLenum format, int width, int height) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, width, height);
    return texture;
}

GLuint makeFramebuffer(GLuint color, GLuint depth, const char* what) {
    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    if (depth != 0)
        glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    glNamedFramebufferDrawBuffer(fbo, GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    SP_CHECK(status == GL_FRAMEBUFFER_COMPLETE, InvalidState, "ScreenOcclusion::ScreenOcclusion(): the ",
             what, " framebuffer is incomplete (status 0x", std::hex, status, ")");
    return fbo;
}

} // namespace

ScreenOcclusion::ScreenOcclusion(int viewWidth, int viewHeight) {
    SP_CHECK(viewWidth > 0 && viewHeight > 0, InvalidArgument, "ScreenOcclusion::ScreenOcclusion(): a ",
             viewWidth, "x", viewHeight, " view");
    const int scale = scaleFor(viewWidth, viewHeight);
    width_ = (viewWidth + scale - 1) / scale;
    height_ = (viewHeight + scale - 1) / scale;
    depth_ = makeTexture(GL_R32F, width_, height_);
    glCreateRenderbuffers(1, &depthBuffer_);
    glNamedRenderbufferStorage(depthBuffer_, GL_DEPTH_COMPONENT32F, width_, height_);
    depthFbo_ = makeFramebuffer(depth_, depthBuffer_, "depth");
    raw_ = makeTexture(GL_R8, width_, height_);
    rawFbo_ = makeFramebuffer(raw_, 0, "occlusion");
    occlusion_ = makeTexture(GL_R8, width_, height_);
    occlusionFbo_ = makeFramebuffer(occlusion_, 0, "blurred occlusion");
    glCreateVertexArrays(1, &emptyVao_);
}

ScreenOcclusion::~ScreenOcclusion() {
    const GLuint fbos[] = {depthFbo_, rawFbo_, occlusionFbo_};
    glDeleteFramebuffers(3, fbos);
    const GLuint textures[] = {depth_, raw_, occlusion_};
    glDeleteTextures(3, textures);
    glDeleteRenderbuffers(1, &depthBuffer_);
    glDeleteVertexArrays(1, &emptyVao_);
}

void ScreenOcclusion::compute(ShaderProgram& occlusion, ShaderProgram& blur, float focalLength, float radius,
                              float intensity) {
    glDisable(GL_DEPTH_TEST);
    glViewport(0, 0, width_, height_);
    glBindVertexArray(emptyVao_);
    glBindImageTexture(0, depth_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);

    glBindFramebuffer(GL_FRAMEBUFFER, rawFbo_);
    occlusion.use();
    // At most 32 texels: further, the probes' own occlusion takes over, and a software rasteriser's caches
    // would miss on every step.
    occlusion.set("uCamera", Eigen::Vector3f(focalLength, radius, 32.0f));
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindFramebuffer(GL_FRAMEBUFFER, occlusionFbo_);
    blur.use();
    blur.set("uIntensity", intensity);
    glBindImageTexture(1, raw_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
}

} // namespace sp::render
