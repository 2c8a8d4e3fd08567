#include "core/render/shadow_maps.h"

#include <epoxy/gl.h>

#include <cmath>

#include <Eigen/Geometry>

#include "core/base/log.h"
#include "core/render/shaders.h"

namespace sp::render {
namespace {

// World -> GL eye for an eye at `eye` looking along unit `forward`.
Eigen::Matrix4d lookAlong(const Eigen::Vector3d& eye, const Eigen::Vector3d& forward) {
    const Eigen::Vector3d up =
        std::abs(forward.z()) < 0.99 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d right = forward.cross(up).normalized();
    const Eigen::Vector3d trueUp = right.cross(forward);
    Eigen::Matrix4d view = Eigen::Matrix4d::Identity();
    view.block<1, 3>(0, 0) = right.transpose();
    view.block<1, 3>(1, 0) = trueUp.transpose();
    view.block<1, 3>(2, 0) = -forward.transpose();
    view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
    return view;
}

Eigen::Matrix4d orthographic(double halfSize, double nearClip, double farClip) {
    Eigen::Matrix4d p = Eigen::Matrix4d::Identity();
    p(0, 0) = p(1, 1) = 1.0 / halfSize;
    p(2, 2) = -2.0 / (farClip - nearClip);
    p(2, 3) = -(farClip + nearClip) / (farClip - nearClip);
    return p;
}

Eigen::Matrix4d perspective(double halfAngle, double nearClip, double farClip) {
    Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
    p(0, 0) = p(1, 1) = 1.0 / std::tan(halfAngle);
    p(2, 2) = -(farClip + nearClip) / (farClip - nearClip);
    p(2, 3) = -2.0 * farClip * nearClip / (farClip - nearClip);
    p(3, 2) = -1.0;
    return p;
}

// Everything the maps depend on, as numbers: comparing it is far cheaper than rendering the maps.
std::vector<double> shadowSignature(const Scene& scene, int resolution) {
    std::vector<double> signature{double(scene.uid()), double(resolution)};
    // Handles are left out: a world re-adds its lights every frame, so only their values count.
    scene.forEachLight([&](LightId, const Light& light) {
        signature.insert(signature.end(),
                         {double(light.type), light.castShadows ? 1.0 : 0.0, light.position.x(),
                          light.position.y(), light.position.z(), light.direction.x(), light.direction.y(),
                          light.direction.z(), light.outerConeDeg});
    });
    scene.forEachInstance([&](InstanceId, const Instance& instance) {
        if (!instance.visible)
            return; // invisible instances neither cast shadows nor widen the scene's bounds
        signature.insert(signature.end(),
                         {double(instance.mesh.index), double(instance.mesh.generation),
                          double(scene.meshRevision(instance.mesh)), instance.castShadows ? 1.0 : 0.0});
        const Eigen::Matrix4d& m = instance.transform.matrix();
        signature.insert(signature.end(), m.data(), m.data() + 16);
    });
    return signature;
}

} // namespace

ShadowMaps::~ShadowMaps() {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
}

void ShadowMaps::ensure(int resolution) {
    if (resolution == resolution_)
        return;
    glDeleteFramebuffers(1, &fbo_);
    glDeleteTextures(1, &texture_);
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture_);
    glTextureStorage3D(texture_, 1, GL_DEPTH_COMPONENT32F, resolution, resolution, shaders::kMaxShadowMaps);
    // Gathered and compared in the shader (see shadowFactor() in shaders.cpp), never filtered.
    glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture_, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    glCreateFramebuffers(1, &fbo_);
    glNamedFramebufferDrawBuffer(fbo_, GL_NONE);
    resolution_ = resolution;
}

std::size_t ShadowMaps::render(const Scene& scene, int resolution, GpuSceneCache& cache,
                               ShaderProgram& depthProgram) {
    std::vector<double> signature = shadowSignature(scene, resolution);
    if (texture_ != 0 && signature == signature_)
        return 0;
    signature_ = std::move(signature);
    std::vector<ShadowInfo>& infos = infos_;
    infos.clear();
    Eigen::Vector3d centre;
    double radius = 0.0;
    scene.bounds(centre, radius);
    if (radius <= 0.0)
        return 0;
    int skipped = 0;
    int ordinal = -1;
    scene.forEachLight([&](LightId, const Light& light) {
        ++ordinal;
        if (!light.castShadows || light.type == LightType::Point)
            return;
        if (infos.size() >= std::size_t(shaders::kMaxShadowMaps)) {
            ++skipped;
            return;
        }
        ShadowInfo info;
        info.lightOrdinal = ordinal;
        info.layer = static_cast<int>(infos.size());
        const Eigen::Vector3d forward = light.direction.normalized();
        Eigen::Matrix4d projection;
        Eigen::Matrix4d view;
        if (light.type == LightType::Directional) {
            view = lookAlong(centre - forward * (2.0 * radius), forward);
            projection = orthographic(radius, 0.0, 4.0 * radius);
            info.texel = float(2.0 * radius / resolution);
        } else {
            const double halfAngle = std::min(light.outerConeDeg * M_PI / 180.0 + 0.05, 1.5);
            const double farClip = (light.position - centre).norm() + radius;
            const double nearClip = std::max(0.02, farClip * 1e-3);
            view = lookAlong(light.position, forward);
            projection = perspective(halfAngle, nearClip, farClip);
            info.texel = float(2.0 * std::tan(halfAngle) / resolution);
            info.perspective = true;
        }
        const Eigen::Matrix4d lightProjection = projection * view;
        info.worldToClip = lightProjection.cast<float>();
        infos.push_back(info);

        ensure(resolution);
        glNamedFramebufferTextureLayer(fbo_, GL_DEPTH_ATTACHMENT, texture_, 0, info.layer);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, resolution, resolution);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        // Slope-scaled offset against acne; the lighting pass adds a normal offset of 1.5 texels.
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(2.0f, 2.0f);
        glClear(GL_DEPTH_BUFFER_BIT);
        depthProgram.use();
        scene.forEachInstance([&](InstanceId, const Instance& instance) {
            if (!instance.visible || !instance.castShadows)
                return;
            // The level of detail whose error stays within half a shadow-map texel.
            Eigen::Vector3d centre;
            double radius = 0.0;
            scene.boundingSphere(instance, centre, radius);
            const double texel = info.perspective
                                     ? info.texel * std::max((centre - light.position).norm() - radius, 0.02)
                                     : double(info.texel);
            const GpuMesh& mesh = cache.mesh(scene, scene.lodFor(instance.mesh, radius / texel));
            depthProgram.set("uModelLightProjection",
                             Eigen::Matrix4f((lightProjection * instance.transform.matrix()).cast<float>()));
            glBindVertexArray(mesh.vao);
            for (const Submesh& sub : mesh.submeshes)
                glDrawElements(GL_TRIANGLES, GLsizei(sub.indexCount), GL_UNSIGNED_INT,
                               reinterpret_cast<const void*>(std::uintptr_t(sub.firstIndex) * 4));
        });
    });
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (skipped > 0 && !warnedTooMany_) {
        SP_LOG("render: ", skipped, " shadow-casting light(s) beyond the first ", shaders::kMaxShadowMaps,
               " are rendered without shadows");
        warnedTooMany_ = true;
    }
    return infos.size();
}

} // namespace sp::render
