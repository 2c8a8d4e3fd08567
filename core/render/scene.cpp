#include "core/render/scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/base/error.h"

namespace sp::render {
namespace {
std::atomic<std::uint64_t> gNextSceneUid{1};
}

Scene::Scene() : uid_(gNextSceneUid++) {}

MeshId Scene::addMesh(MeshData mesh, std::string sharedKey) {
    mesh.validate("Scene::addMesh");
    MeshEntry entry;
    entry.data = std::move(mesh);
    entry.revision = nextRevision_++;
    entry.sharedKey = std::move(sharedKey);
    describe(entry);
    return meshes_.insert(std::move(entry));
}

void Scene::describe(MeshEntry& entry) {
    entry.data.bounds(entry.min, entry.max);
    entry.convexFaceted = entry.data.faceted() && entry.data.convex(); // faceted() first: it is cheap
    entry.windingSpread.reset();
    entry.longestEdge.reset();
}

void Scene::updateMesh(MeshId id, MeshData mesh) {
    MeshEntry& entry = meshes_.get(id, "Scene::updateMesh");
    mesh.validate("Scene::updateMesh");
    instances_.forEach([&](InstanceId instanceId, const Instance& instance) {
        SP_CHECK(instance.mesh != id || mesh.submeshCount() == entry.data.submeshCount(), InvalidArgument,
                 "Scene::updateMesh(): ", id, " has ", entry.data.submeshCount(), " submeshes used by ",
                 instanceId, "; the new mesh has ", mesh.submeshCount());
    });
    entry.data = std::move(mesh);
    entry.revision = nextRevision_++;
    entry.sharedKey.clear();
    describe(entry);
}

void Scene::deformMesh(MeshId id, std::span<const Eigen::Vector3f> positions,
                       std::span<const Eigen::Vector3f> normals) {
    MeshEntry& entry = meshes_.get(id, "Scene::deformMesh");
    SP_CHECK(positions.size() == entry.data.positions.size() && normals.size() == positions.size(),
             InvalidArgument, "Scene::deformMesh(): ", id, " has ", entry.data.positions.size(),
             " vertices, got ", positions.size(), " positions and ", normals.size(), " normals");
    entry.data.positions.assign(positions.begin(), positions.end());
    entry.data.normals.assign(normals.begin(), normals.end());
    entry.revision = nextRevision_++;
    entry.sharedKey.clear();
    describe(entry); // smooth meshes skip the convexity test (faceted() first): the bounds and one pass
}

void Scene::removeMesh(MeshId id) {
    meshes_.get(id, "Scene::removeMesh");
    instances_.forEach([&](InstanceId instanceId, const Instance& instance) {
        SP_CHECK(instance.mesh != id, InvalidState, "Scene::removeMesh(): ", id, " is used by ", instanceId);
    });
    meshes_.forEach([&](MeshId owner, const MeshEntry& entry) {
        for (const MeshLod& lod : entry.lods)
            SP_CHECK(lod.mesh != id, InvalidState, "Scene::removeMesh(): ", id, " is a level of detail of ",
                     owner);
    });
    meshes_.remove(id, "Scene::removeMesh");
}

const MeshData& Scene::mesh(MeshId id) const {
    return meshes_.get(id, "Scene::mesh").data;
}
std::uint64_t Scene::meshRevision(MeshId id) const {
    return meshes_.get(id, "Scene::meshRevision").revision;
}
const std::string& Scene::meshSharedKey(MeshId id) const {
    return meshes_.get(id, "Scene::meshSharedKey").sharedKey;
}
bool Scene::meshConvexFaceted(MeshId id) const {
    return meshes_.get(id, "Scene::meshConvexFaceted").convexFaceted;
}
float Scene::meshWindingSpread(MeshId id) const {
    const MeshEntry& entry = meshes_.get(id, "Scene::meshWindingSpread");
    if (!entry.windingSpread)
        entry.windingSpread = entry.data.windingSpread();
    return *entry.windingSpread;
}

float Scene::meshLongestEdge(MeshId id) const {
    const MeshEntry& entry = meshes_.get(id, "Scene::meshLongestEdge");
    if (!entry.longestEdge)
        entry.longestEdge = entry.data.longestEdge();
    return *entry.longestEdge;
}

TextureId Scene::addTexture(TextureImage image, TextureEncoding encoding, std::string sharedKey) {
    SP_CHECK(image.width > 0 && image.height > 0 &&
                 image.rgba.size() == std::size_t(image.width) * image.height * 4,
             InvalidArgument, "Scene::addTexture(): image '", image.source, "' is not ", image.width, "x",
             image.height, " RGBA8");
    return textures_.insert({std::move(image), encoding, std::move(sharedKey)});
}

void Scene::removeTexture(TextureId id) {
    textures_.get(id, "Scene::removeTexture");
    materials_.forEach([&](MaterialId materialId, const Material& m) {
        SP_CHECK(m.baseColorTexture != id && m.roughnessMetallicTexture != id && m.normalTexture != id,
                 InvalidState, "Scene::removeTexture(): ", id, " is used by ", materialId);
    });
    textures_.remove(id, "Scene::removeTexture");
}

const TextureImage& Scene::texture(TextureId id) const {
    return textures_.get(id, "Scene::texture").image;
}
TextureEncoding Scene::textureEncoding(TextureId id) const {
    return textures_.get(id, "Scene::textureEncoding").encoding;
}
const std::string& Scene::textureSharedKey(TextureId id) const {
    return textures_.get(id, "Scene::textureSharedKey").sharedKey;
}

void Scene::checkMaterialTextures(const Material& material, const char* function) const {
    for (const auto& texture :
         {material.baseColorTexture, material.roughnessMetallicTexture, material.normalTexture})
        if (texture)
            textures_.get(*texture, function);
}

MaterialId Scene::addMaterial(const Material& material) {
    material.validate("Scene::addMaterial");
    checkMaterialTextures(material, "Scene::addMaterial");
    return materials_.insert(material);
}

void Scene::setMaterial(MaterialId id, const Material& material) {
    Material& slot = materials_.get(id, "Scene::setMaterial");
    material.validate("Scene::setMaterial");
    checkMaterialTextures(material, "Scene::setMaterial");
    slot = material;
}

void Scene::removeMaterial(MaterialId id) {
    materials_.get(id, "Scene::removeMaterial");
    instances_.forEach([&](InstanceId instanceId, const Instance& instance) {
        for (MaterialId used : instance.materials)
            SP_CHECK(used != id, InvalidState, "Scene::removeMaterial(): ", id, " is used by ", instanceId);
    });
    materials_.remove(id, "Scene::removeMaterial");
}

const Material& Scene::material(MaterialId id) const {
    return materials_.get(id, "Scene::material");
}

std::uint32_t Scene::materialIdValue(MaterialId id) const {
    const Material& m = materials_.get(id, "Scene::materialIdValue");
    return m.id != 0 ? m.id : id.index + 1;
}

Scene::TexturedFactors Scene::texturedFactors() const {
    TexturedFactors textured;
    materials_.forEach([&](MaterialId, const Material& m) {
        textured.baseColor = textured.baseColor || m.baseColorTexture.has_value();
        textured.roughnessMetallic = textured.roughnessMetallic || m.roughnessMetallicTexture.has_value();
    });
    return textured;
}

LightId Scene::addLight(const Light& light) {
    light.validate("Scene::addLight");
    SP_CHECK(lights_.size() < kMaxLights, InvalidState, "Scene::addLight(): the scene already has ",
             kMaxLights, " lights (the maximum)");
    return lights_.insert(light);
}

void Scene::setLight(LightId id, const Light& light) {
    Light& slot = lights_.get(id, "Scene::setLight");
    light.validate("Scene::setLight");
    slot = light;
}

void Scene::removeLight(LightId id) {
    lights_.remove(id, "Scene::removeLight");
}
const Light& Scene::light(LightId id) const {
    return lights_.get(id, "Scene::light");
}

void Scene::checkInstance(const Instance& instance, const char* function) const {
    const MeshData& mesh = meshes_.get(instance.mesh, function).data;
    SP_CHECK(instance.materials.size() == mesh.submeshCount(), InvalidArgument, function,
             "(): ", instance.mesh, " has ", mesh.submeshCount(), " submesh slot(s) but ",
             instance.materials.size(), " material(s) were given");
    SP_CHECK(instance.objectIds.size() == mesh.submeshCount(), InvalidArgument, function,
             "(): ", instance.mesh, " has ", mesh.submeshCount(), " submesh slot(s) but ",
             instance.objectIds.size(), " object id(s) were given");
    for (MaterialId material : instance.materials)
        materials_.get(material, function);
    for (std::size_t i = 0; i < instance.objectIds.size(); ++i)
        SP_CHECK(instance.objectIds[i] != 0, InvalidArgument, function, "(): objectIds[", i,
                 "] is 0, which is reserved for the background");
    SP_CHECK(instance.transform.matrix().allFinite(), InvalidArgument, function,
             "(): transform is not finite");
}

InstanceId Scene::addInstance(const Instance& instance) {
    checkInstance(instance, "Scene::addInstance");
    return instances_.insert(instance);
}

void Scene::setInstance(InstanceId id, const Instance& instance) {
    Instance& slot = instances_.get(id, "Scene::setInstance");
    checkInstance(instance, "Scene::setInstance");
    slot = instance;
}

void Scene::setTransform(InstanceId id, const Eigen::Affine3d& transform) {
    Instance& slot = instances_.get(id, "Scene::setTransform");
    SP_CHECK(transform.matrix().allFinite(), InvalidArgument,
             "Scene::setTransform(): transform is not finite");
    slot.transform = transform;
}

void Scene::setIrradianceVolume(std::shared_ptr<const IrradianceVolume> volume) {
    if (volume && volume != irradianceVolume_) // the same volume again (every frame while still) was checked
        volume->validate("Scene::setIrradianceVolume");
    irradianceVolume_ = std::move(volume);
}

void Scene::removeInstance(InstanceId id) {
    instances_.remove(id, "Scene::removeInstance");
}
const Instance& Scene::instance(InstanceId id) const {
    return instances_.get(id, "Scene::instance");
}

void Scene::setMeshLods(MeshId id, std::vector<MeshLod> lods) {
    MeshEntry& entry = meshes_.get(id, "Scene::setMeshLods");
    float previous = 0.0f;
    for (const MeshLod& lod : lods) {
        const MeshEntry& level = meshes_.get(lod.mesh, "Scene::setMeshLods");
        SP_CHECK(lod.mesh != id && level.lods.empty(), InvalidArgument, "Scene::setMeshLods(): ", lod.mesh,
                 " cannot be a level of ", id, " (it is the mesh itself or has levels of its own)");
        SP_CHECK(level.data.submeshCount() == entry.data.submeshCount(), InvalidArgument,
                 "Scene::setMeshLods(): level ", lod.mesh, " has ", level.data.submeshCount(), " submeshes, ",
                 id, " has ", entry.data.submeshCount());
        SP_CHECK(std::isfinite(lod.relativeError) && lod.relativeError >= previous, InvalidArgument,
                 "Scene::setMeshLods(): relative errors must be finite and increase, got ", lod.relativeError,
                 " after ", previous);
        previous = lod.relativeError;
    }
    for (MeshLod& lod : lods)
        lod.surfaceError = std::max(lod.surfaceError, lod.relativeError);
    entry.lods = std::move(lods);
}

const std::vector<MeshLod>& Scene::meshLods(MeshId id) const {
    return meshes_.get(id, "Scene::meshLods").lods;
}

MeshLod Scene::chooseLod(MeshId id, double radiusInPixels) const {
    MeshLod chosen{id, 0.0f, 0.0f};
    for (const MeshLod& lod : meshes_.get(id, "Scene::lodFor").lods) {
        if (double(lod.relativeError) * radiusInPixels > 0.5)
            break;
        chosen = lod;
    }
    return chosen;
}

void Scene::boundingSphere(const Instance& instance, Eigen::Vector3d& centre, double& radius) const {
    const MeshEntry& entry = meshes_.get(instance.mesh, "Scene::boundingSphere");
    centre = instance.transform * (0.5 * (entry.min + entry.max)).cast<double>();
    radius = 0.5 * (entry.max - entry.min).cast<double>().norm() *
             instance.transform.linear().colwise().norm().maxCoeff();
}

Eigen::AlignedBox3d Scene::boundingBox(const Instance& instance) const {
    const MeshEntry& entry = meshes_.get(instance.mesh, "Scene::boundingBox");
    Eigen::AlignedBox3d box;
    for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d local((corner & 1) ? entry.max.x() : entry.min.x(),
                                    (corner & 2) ? entry.max.y() : entry.min.y(),
                                    (corner & 4) ? entry.max.z() : entry.min.z());
        box.extend(instance.transform * local);
    }
    return box;
}

bool Scene::reachesInside(std::span<const Eigen::Vector4d> planes, const Eigen::Vector3d& centre,
                          double radius) {
    return std::none_of(planes.begin(), planes.end(), [&](const Eigen::Vector4d& plane) {
        return plane.head<3>().dot(centre) + plane.w() < -radius; // wholly outside this plane
    });
}

void Scene::bounds(Eigen::Vector3d& centre, double& radius, std::span<const Eigen::Vector4d> within) const {
    Eigen::AlignedBox3d box;
    instances_.forEach([&](InstanceId, const Instance& instance) {
        if (!instance.visible)
            return;
        if (!within.empty()) {
            Eigen::Vector3d sphereCentre;
            double sphereRadius = 0.0;
            boundingSphere(instance, sphereCentre, sphereRadius);
            if (!reachesInside(within, sphereCentre, sphereRadius))
                return;
        }
        box.extend(boundingBox(instance));
    });
    if (box.isEmpty()) {
        centre.setZero();
        radius = 0.0;
        return;
    }
    centre = box.center();
    radius = 0.5 * box.diagonal().norm();
}

} // namespace sp::render
