#include "core/render/renderer.h"

#include <epoxy/gl.h>

#include <cmath>
#include <string>

#include "core/base/error.h"
#include "core/render/framebuffers.h"
#include "core/render/gpu_scene_cache.h"
#include "core/render/shader_program.h"
#include "core/render/shaders.h"
#include "core/render/shadow_maps.h"

namespace sp::render {

Renderer::Renderer(const GlContext& context) : context_(context) {
    context_.makeCurrent();
    geometry_ =
        std::make_unique<ShaderProgram>("geometry", shaders::kGeometryVertex, shaders::kGeometryFragment);
    shadow_ = std::make_unique<ShaderProgram>("shadow", shaders::kShadowVertex, shaders::kShadowFragment);
    lighting_ =
        std::make_unique<ShaderProgram>("lighting", shaders::kFullscreenVertex, shaders::kLightingFragment);
    tonemap_ =
        std::make_unique<ShaderProgram>("tonemap", shaders::kFullscreenVertex, shaders::kTonemapFragment);
    shadowMaps_ = std::make_unique<ShadowMaps>();
    glCreateVertexArrays(1, &emptyVao_);
    // Readbacks of 3-channel and 16-bit images have rows that are not multiples of 4 bytes.
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
}

Renderer::~Renderer() {
    context_.makeCurrent();
    caches_.clear();
    shadowMaps_.reset();
    glDeleteVertexArrays(1, &emptyVao_);
}

const RenderStats& Renderer::stats() const {
    return stats_;
}
void Renderer::resetStats() {
    stats_ = RenderStats();
}
void Renderer::releaseScene(const Scene& scene) {
    caches_.erase(scene.uid());
}

GpuSceneCache& Renderer::cacheFor(const Scene& scene) {
    auto& cache = caches_[scene.uid()];
    if (!cache)
        cache = std::make_unique<GpuSceneCache>();
    return *cache;
}

void Renderer::render(const Scene& scene, const Camera& camera, const PassSet& passes, Framebuffers& fb) {
    camera.params.validate("Renderer::render");
    GpuSceneCache& cache = cacheFor(scene);
    const std::uint64_t meshUploads = cache.meshUploads(), textureUploads = cache.textureUploads();
    fb.ensure(camera.params.width, camera.params.height, passes);
    glDisable(GL_CULL_FACE); // two-sided: imported meshes have unreliable winding
    glDisable(GL_BLEND);
    if (passes.gbuffer)
        geometryPass(scene, camera, cache, fb);
    if (passes.lighting)
        lightingPass(scene, camera, passes.shadow, cache, fb);
    if (passes.tonemap)
        tonemapPass(camera, fb);
    stats_.meshUploads += cache.meshUploads() - meshUploads;
    stats_.textureUploads += cache.textureUploads() - textureUploads;
    ++stats_.frames;
}

void Renderer::geometryPass(const Scene& scene, const Camera& camera, GpuSceneCache& cache,
                            Framebuffers& fb) {
    glBindFramebuffer(GL_FRAMEBUFFER, fb.gbufferFbo);
    glViewport(0, 0, fb.width, fb.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    const float zero[4] = {0, 0, 0, 0};
    const GLuint zeroIds[4] = {0, 0, 0, 0};
    for (int i = 0; i < shaders::GIds; ++i)
        glClearBufferfv(GL_COLOR, i, zero);
    glClearBufferuiv(GL_COLOR, shaders::GIds, zeroIds);
    glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);

    // The projection is flipped vertically so that GL's bottom row holds image row 0 and glReadPixels
    // returns the top image row first; depth and ids are unaffected.
    const Eigen::Matrix4d worldToCamera = camera.pose.inverse(Eigen::Isometry).matrix();
    const Eigen::Matrix4d viewProjection = camera.projectionMatrix(true) * camera.viewMatrix();
    ShaderProgram& program = *geometry_;
    program.use();
    program.set("uCameraPosition", Eigen::Vector3f(camera.pose.translation().cast<float>()));
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        if (!instance.visible)
            return;
        const GpuMesh& mesh = cache.mesh(scene, instance.mesh);
        const Eigen::Matrix4d model = instance.transform.matrix();
        program.set("uModel", Eigen::Matrix4f(model.cast<float>()));
        program.set("uNormalMatrix",
                    Eigen::Matrix3f(instance.transform.linear().inverse().transpose().cast<float>()));
        program.set("uModelToCamera", Eigen::Matrix4f((worldToCamera * model).cast<float>()));
        program.set("uModelViewProjection", Eigen::Matrix4f((viewProjection * model).cast<float>()));
        glBindVertexArray(mesh.vao);
        for (std::size_t slot = 0; slot < mesh.submeshes.size(); ++slot) {
            const MaterialId materialId = instance.materials[slot];
            const Material& material = scene.material(materialId);
            program.set("uBaseColor", material.baseColor);
            program.set("uRoughness", material.roughness);
            program.set("uMetallic", material.metallic);
            program.set("uAo", material.ambientOcclusion);
            program.set("uEmissive", material.emissive);
            program.set("uObjectId", instance.objectIds[slot]);
            program.set("uMaterialId", scene.materialIdValue(materialId));
            const std::optional<TextureId> textures[3] = {
                material.baseColorTexture, material.roughnessMetallicTexture, material.normalTexture};
            const char* flags[3] = {"uHasBaseColorTexture", "uHasRoughnessMetallicTexture",
                                    "uHasNormalTexture"};
            for (int t = 0; t < 3; ++t) {
                program.set(flags[t], textures[t] ? 1 : 0);
                glBindTextureUnit(t, textures[t] ? cache.texture(scene, *textures[t]) : 0);
            }
            const Submesh& sub = mesh.submeshes[slot];
            glDrawElements(GL_TRIANGLES, GLsizei(sub.indexCount), GL_UNSIGNED_INT,
                           reinterpret_cast<const void*>(std::uintptr_t(sub.firstIndex) * 4));
        }
    });
    glBindVertexArray(0);
    ++stats_.gbufferPasses;
}

void Renderer::lightingPass(const Scene& scene, const Camera& camera, bool shadows, GpuSceneCache& cache,
                            Framebuffers& fb) {
    std::vector<ShadowInfo> shadowInfos;
    if (shadows) {
        shadowInfos = shadowMaps_->render(scene, camera.params.shadowResolution, cache, *shadow_);
        stats_.shadowPasses += shadowInfos.size();
    }
    ShaderProgram& program = *lighting_;
    for (const ShadowInfo& info : shadowInfos) {
        const std::string index = "[" + std::to_string(info.layer) + "]";
        program.set("uShadowMatrix" + index, info.worldToClip);
        program.set("uShadowTexel" + index, info.texel);
        program.set("uShadowPerspective" + index, info.perspective ? 1 : 0);
    }
    int count = 0;
    scene.forEachLight([&](LightId id, const Light& light) {
        const std::string index = "[" + std::to_string(count) + "]";
        int layer = -1;
        for (const ShadowInfo& info : shadowInfos)
            if (info.light == id)
                layer = info.layer;
        program.set("uLightType" + index, static_cast<int>(light.type));
        program.set("uLightRadiance" + index, Eigen::Vector3f(light.color * light.intensity));
        program.set("uLightPosition" + index, Eigen::Vector3f(light.position.cast<float>()));
        program.set("uLightDirection" + index, Eigen::Vector3f(light.direction.normalized().cast<float>()));
        program.set("uLightRange" + index, light.range);
        program.set("uLightCone" + index,
                    Eigen::Vector2f(std::cos(light.innerConeDeg * float(M_PI) / 180.0f),
                                    std::cos(light.outerConeDeg * float(M_PI) / 180.0f)));
        program.set("uLightShadow" + index, layer);
        ++count;
    });
    program.set("uLightCount", count);
    program.set("uCameraPosition", Eigen::Vector3f(camera.pose.translation().cast<float>()));
    program.set("uAmbient", scene.environment().ambient);
    program.set("uBackground", scene.environment().background);

    glBindFramebuffer(GL_FRAMEBUFFER, fb.lightingFbo);
    glViewport(0, 0, fb.width, fb.height);
    glDisable(GL_DEPTH_TEST);
    for (int t :
         {shaders::GPosition, shaders::GNormal, shaders::GBaseColor, shaders::GParams, shaders::GEmissive})
        glBindTextureUnit(t, fb.gbufferTextures[t]);
    glBindTextureUnit(7, shadowInfos.empty() ? 0 : shadowMaps_->texture());
    program.use();
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    ++stats_.lightingPasses;
}

void Renderer::tonemapPass(const Camera& camera, Framebuffers& fb) {
    glBindFramebuffer(GL_FRAMEBUFFER, fb.tonemapFbo);
    glViewport(0, 0, fb.width, fb.height);
    glDisable(GL_DEPTH_TEST);
    glBindTextureUnit(0, fb.lightingTextures[shaders::LHdr]);
    ShaderProgram& program = *tonemap_;
    program.set("uExposure", camera.params.exposure);
    program.set("uToneMap", static_cast<int>(camera.params.toneMap));
    program.use();
    glBindVertexArray(emptyVao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    ++stats_.tonemapPasses;
}

} // namespace sp::render
