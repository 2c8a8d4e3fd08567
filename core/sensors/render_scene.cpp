#include "core/sensors/render_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "core/animation/skeletal_mesh_component.h"
#include "core/base/log.h"
#include "core/gameplay/zone_graph.h"
#include "core/procedural/spline_component.h"
#include "core/render/content_key.h"
#include "core/render/mesh_import.h"
#include "core/render/mesh_lods.h"
#include "core/render/primitives.h"
#include "core/sensors/light_component.h"
#include "core/sensors/linear_color.h"
#include "core/sensors/rect_light_component.h"
#include "core/sensors/sky_atmosphere_component.h"
#include "core/sensors/sky_light_component.h"
#include "core/sensors/spot_light_component.h"
#include "core/world/static_mesh_component.h"
#include "core/world/world.h"

namespace sp::sensors {
namespace {

constexpr std::string_view kBasicShapesPrefix = "/Engine/BasicShapes/";

// The built-in shapes, sized like UStaticMeshComponent's bounds (unit extents, centred).
std::optional<sp::render::MeshData> basicShape(std::string_view name) {
    if (!name.starts_with(kBasicShapesPrefix))
        return std::nullopt;
    name.remove_prefix(kBasicShapesPrefix.size());
    if (name == "Cube")
        return sp::render::primitives::box();
    if (name == "Sphere")
        return sp::render::primitives::sphere(0.5f, 48, 24);
    if (name == "Cylinder")
        return sp::render::primitives::cylinder(0.5f, 1.0f, 48);
    if (name == "Plane")
        return sp::render::primitives::plane();
    return std::nullopt;
}

// Coarser versions of the round built-in shapes, with the largest deviation of their outline from the round
// one relative to the shape's bounding radius (half the diagonal of its unit box): a polygon of `segments`
// sides sags by r (1 - cos(pi / segments)), for a UV sphere's outline as for a cylinder's sides. A sphere's
// quads sag about twice that at their centres, r (1 - cos^2(pi / segments)), along the line of sight: depth,
// not the image, moves, but a shadow lookup must clear it (MeshLod::surfaceError).
// Levels close together, so that the one drawn (the coarsest within half a pixel) is near that bound: with
// 24, 12 and 8 segments only, a sphere of 30 pixels drew 576 triangles where 324 keep within it, and on a
// software rasteriser its small triangles cost far more than their pixels (Table 3, N = 64, 1080p: 15%).
struct ShapeLevel {
    sp::render::MeshData data;
    float relativeError, surfaceError;
};
std::vector<ShapeLevel> basicShapeLods(std::string_view name) {
    std::vector<ShapeLevel> lods;
    if (!name.starts_with(kBasicShapesPrefix))
        return lods;
    name.remove_prefix(kBasicShapesPrefix.size());
    const double halfDiagonal = 0.5 * std::sqrt(3.0);
    for (int segments : {40, 32, 28, 24, 20, 18, 16, 14, 12, 10, 8}) {
        const double angle = M_PI / segments;
        const auto outline = float(0.5 * (1.0 - std::cos(angle)) / halfDiagonal);
        if (name == "Sphere")
            lods.push_back({sp::render::primitives::sphere(0.5f, segments, segments / 2), outline,
                            float(0.5 * (1.0 - std::cos(angle) * std::cos(angle)) / halfDiagonal)});
        else if (name == "Cylinder")
            lods.push_back({sp::render::primitives::cylinder(0.5f, 1.0f, segments), outline, outline});
    }
    return lods;
}

// Mesh-to-world, scale included (FTransform::toIsometry drops the scale).
Eigen::Affine3d worldTransform(const USceneComponent& component) {
    const FTransform transform = component.GetComponentTransform();
    Eigen::Affine3d result = Eigen::Affine3d::Identity();
    result.translate(transform.Translation.toEigen());
    result.rotate(transform.Rotation.toEigen().normalized());
    result.scale(transform.Scale3D.toEigen());
    return result;
}

sp::render::Light toRenderLight(const ULightComponent& component) {
    sp::render::Light light;
    light.color = rgb(component.LightColor);
    light.intensity = component.Intensity;
    light.castShadows = component.bCastShadows;
    light.position = component.GetComponentLocation().toEigen();
    light.direction = component.GetForwardVector().toEigen();
    if (const auto* spot = dynamic_cast<const USpotLightComponent*>(&component)) {
        light.type = sp::render::LightType::Spot;
        light.range = spot->AttenuationRadius;
        light.innerConeDeg = spot->InnerConeAngle;
        light.outerConeDeg = spot->OuterConeAngle;
    } else if (const auto* point = dynamic_cast<const UPointLightComponent*>(&component)) {
        light.type = sp::render::LightType::Point;
        light.range = point->AttenuationRadius;
    } else if (const auto* rect = dynamic_cast<const URectLightComponent*>(&component)) {
        // Its size is its own: the component's scale does not stretch it (as in Unreal).
        light.type = sp::render::LightType::Rect;
        light.range = rect->AttenuationRadius;
        light.right = component.GetRightVector().toEigen();
        light.up = component.GetUpVector().toEigen();
        light.width = rect->SourceWidth;
        light.height = rect->SourceHeight;
    } else {
        light.type = sp::render::LightType::Directional;
    }
    return light;
}

} // namespace

void RenderScene::logOnce(const std::string& key, const std::string& message) {
    if (logged_.insert(key).second)
        SP_LOG(message);
}

void RenderScene::track(AActor& actor) {
    if (const auto* library = dynamic_cast<const AMaterialLibrary*>(&actor))
        libraries_.add(library);
    else if (auto* roads = dynamic_cast<AZoneGraphData*>(&actor))
        roadData_.add(roads);
}

void RenderScene::untrack(AActor& actor) {
    if (const auto* library = dynamic_cast<const AMaterialLibrary*>(&actor))
        libraries_.remove(library);
    else if (const auto* roads = dynamic_cast<const AZoneGraphData*>(&actor))
        roadData_.remove(roads);
}

void RenderScene::track(UActorComponent& component) {
    if (auto* mesh = dynamic_cast<UStaticMeshComponent*>(&component))
        meshComponents_.add(mesh);
    else if (auto* skinned = dynamic_cast<USkeletalMeshComponent*>(&component))
        skinnedComponents_.add(skinned);
    else if (const auto* spline = dynamic_cast<const USplineComponent*>(&component))
        splines_.add(spline);
    else if (const auto* light = dynamic_cast<const ULightComponent*>(&component))
        lightComponents_.add(light);
    else if (const auto* sky = dynamic_cast<const USkyLightComponent*>(&component))
        skies_.add(sky);
    else if (const auto* atmosphere = dynamic_cast<const USkyAtmosphereComponent*>(&component))
        atmospheres_.add(atmosphere);
}

void RenderScene::untrack(UActorComponent& component) {
    if (const auto* mesh = dynamic_cast<const UStaticMeshComponent*>(&component))
        meshComponents_.remove(mesh);
    else if (const auto* skinned = dynamic_cast<const USkeletalMeshComponent*>(&component))
        skinnedComponents_.remove(skinned);
    else if (const auto* spline = dynamic_cast<const USplineComponent*>(&component))
        splines_.remove(spline);
    else if (const auto* light = dynamic_cast<const ULightComponent*>(&component))
        lightComponents_.remove(light);
    else if (const auto* sky = dynamic_cast<const USkyLightComponent*>(&component))
        skies_.remove(sky);
    else if (const auto* atmosphere = dynamic_cast<const USkyAtmosphereComponent*>(&component))
        atmospheres_.remove(atmosphere);
}

void RenderScene::sync() {
    // Libraries first, because every mesh slot resolves names against them.
    std::map<std::string, FMaterialDesc> library;
    for (const auto& [sequence, materials] : libraries_.items())
        for (const auto& [name, desc] : materials->Materials)
            library.emplace(name, desc); // the first library spawned wins a name clash

    std::set<sp::reflect::ObjectHandle> alive;
    for (const auto& [sequence, mesh] : meshComponents_.items()) {
        alive.insert(mesh->GetHandle());
        syncMesh(*mesh, library);
    }
    for (const auto& [sequence, mesh] : skinnedComponents_.items()) {
        alive.insert(mesh->GetHandle());
        syncSkinnedMesh(*mesh, library);
    }
    // Components that are gone: their instance goes, and so do their ids (never reused).
    for (auto it = instances_.begin(); it != instances_.end();) {
        if (alive.count(it->first)) {
            ++it;
            continue;
        }
        if (it->second.instance.isSet())
            scene_.removeInstance(it->second.instance);
        for (std::uint32_t id : it->second.ids)
            idInfo_.erase(id);
        if (auto skinned = skinned_.find(it->first); skinned != skinned_.end()) {
            removeSkinnedMesh(skinned->second);
            skinned_.erase(skinned);
        }
        it = instances_.erase(it);
    }

    std::set<sp::reflect::ObjectHandle> drawn;
    for (const auto& [sequence, spline] : splines_.items()) {
        if (!spline->bDrawDebug)
            continue;
        drawn.insert(spline->GetHandle());
        syncDebugLine(*spline);
    }
    for (auto it = debugLines_.begin(); it != debugLines_.end();) {
        if (drawn.count(it->first)) {
            ++it;
            continue;
        }
        removeDebugLine(it->second);
        it = debugLines_.erase(it);
    }
    std::set<sp::reflect::ObjectHandle> paved;
    for (const auto& [sequence, data] : roadData_.items()) {
        if (!data->bDrawRoads)
            continue;
        paved.insert(data->GetHandle());
        syncRoads(*data, library);
    }
    for (auto it = roads_.begin(); it != roads_.end();) {
        if (paved.count(it->first)) {
            ++it;
            continue;
        }
        removeRoads(it->second);
        it = roads_.erase(it);
    }

    // The lights are set in place, in play order: removed and added again, they came back in the reverse
    // order of their handles every other frame, which made a still scene's shadow maps be drawn again and
    // its programs (specialised for the lights in order) change each frame.
    std::size_t count = 0;
    for (const auto& [sequence, light] : lightComponents_.items()) {
        if (!light->bVisible)
            continue;
        if (count == sp::render::Scene::kMaxLights) {
            logOnce("lights", "RenderSubsystem: more than " + std::to_string(sp::render::Scene::kMaxLights) +
                                  " lights in the world; the rest are not rendered");
            break;
        }
        sp::render::Light renderLight = toRenderLight(*light);
        renderLight.validate(("light '" + light->GetDebugName() + "'").c_str());
        if (count < lights_.size())
            scene_.setLight(lights_[count], renderLight);
        else
            lights_.push_back(scene_.addLight(renderLight));
        ++count;
    }
    while (lights_.size() > count) {
        scene_.removeLight(lights_.back());
        lights_.pop_back();
    }

    // The first sky light and atmosphere in play; the sun is the first visible directional light.
    const ULightComponent* sun = nullptr;
    for (const auto& [sequence, light] : lightComponents_.items())
        if (light->bVisible && dynamic_cast<const UDirectionalLightComponent*>(light) != nullptr) {
            sun = light;
            break;
        }
    scene_.setEnvironment(
        sky_.update(skies_.items().empty() ? nullptr : skies_.items().begin()->second,
                    atmospheres_.items().empty() ? nullptr : atmospheres_.items().begin()->second, sun,
                    [this](const std::string& key, const std::string& message) { logOnce(key, message); }));
}

void RenderScene::syncMesh(UStaticMeshComponent& component,
                           const std::map<std::string, FMaterialDesc>& library) {
    const MeshEntry* mesh = component.StaticMesh.empty() ? nullptr : meshFor(component.GetMeshAsset());
    if (!mesh) { // no mesh (yet): nothing to draw, but ids already handed out stay
        removeInstanceOf(component.GetHandle());
        return;
    }
    placeInstance(component, mesh->mesh, component.Materials, mesh->importedMaterials, mesh->importedNames,
                  library);
}

void RenderScene::removeInstanceOf(sp::reflect::ObjectHandle component) {
    InstanceEntry& entry = instances_[component];
    if (entry.instance.isSet())
        scene_.removeInstance(entry.instance);
    entry.instance = {};
}

void RenderScene::placeInstance(const UPrimitiveComponent& component, sp::render::MeshId mesh,
                                const std::vector<std::string>& materialNames,
                                const std::vector<sp::render::MaterialId>& imported,
                                const std::vector<std::string>& importedNames,
                                const std::map<std::string, FMaterialDesc>& library,
                                bool affectIndirectLighting) {
    InstanceEntry& entry = instances_[component.GetHandle()];
    const std::size_t slots = scene_.mesh(mesh).submeshCount();
    sp::render::Instance instance;
    instance.mesh = mesh;
    instance.transform = worldTransform(component);
    instance.visible = component.bVisible;
    instance.affectIndirectLighting = affectIndirectLighting;
    for (std::size_t slot = 0; slot < slots; ++slot) {
        const std::string name = slot < materialNames.size() ? materialNames[slot] : std::string();
        std::string slotName = name;
        if (name.empty() && slot < imported.size()) {
            instance.materials.push_back(imported[slot]);
            slotName = importedNames[slot];
        } else {
            instance.materials.push_back(materialFor(name, library));
            if (slotName.empty())
                slotName = "Default";
        }
        if (entry.ids.size() <= slot)
            entry.ids.push_back(nextObjectId_++);
        instance.objectIds.push_back(entry.ids[slot]);
        idInfo_[entry.ids[slot]] = {component.GetHandle(), int(slot), slotName};
    }
    if (entry.instance.isSet())
        scene_.setInstance(entry.instance, instance);
    else
        entry.instance = scene_.addInstance(instance);
}

void RenderScene::syncSkinnedMesh(USkeletalMeshComponent& component,
                                  const std::map<std::string, FMaterialDesc>& library) {
    SkinnedEntry& skinned = skinned_[component.GetHandle()];
    const std::shared_ptr<const sp::animation::SkeletalMeshData>& asset = component.GetAsset();
    if (skinned.asset != asset || skinned.bodyParts != component.bBodyPartIds) {
        // A new mesh (or none, or split otherwise): the instance goes until the new mesh is made (its slots,
        // and so its object ids, may differ).
        removeInstanceOf(component.GetHandle());
        InstanceEntry& entry = instances_[component.GetHandle()];
        if (skinned.asset &&
            skinned.bodyParts != component.bBodyPartIds) { // other slots: new ids (never reused)
            for (std::uint32_t id : entry.ids)
                idInfo_.erase(id);
            entry.ids.clear();
        }
        removeSkinnedMesh(skinned);
        skinned = SkinnedEntry{};
        if (!asset)
            return;
        skinned.asset = asset;
        skinned.bodyParts = component.bBodyPartIds;
        // The component's own copy: its vertices move with its pose (never shared).
        const sp::render::MeshData& bind = *component.renderMesh();
        skinned.mesh = scene_.addMesh(bind);
        addSkinnedLevels(skinned, bind);
        const SkinnedMaterials& materials = skinnedMaterialsFor(asset, component.SkeletalMesh);
        for (std::size_t slot = 0; slot < bind.submeshCount(); ++slot) {
            const std::uint32_t fileSlot = component.materialOfSlot(slot);
            skinned.fileSlots.push_back(fileSlot);
            skinned.importedMaterials.push_back(materials.ids[fileSlot]);
            skinned.importedNames.push_back(materials.names[fileSlot]);
        }
        skinned.poseRevision = component.poseRevision() - 1; // posed below
    }
    if (!asset)
        return;
    if (skinned.poseRevision != component.poseRevision()) {
        const sp::animation::SkeletalMeshData& data = *asset;
        const std::vector<Eigen::Matrix4f> matrices =
            sp::animation::skinningMatrices(component.componentSpaceTransforms(), data.skeleton.inverseBind);
        sp::animation::skin(data.mesh.mesh.positions, data.mesh.mesh.normals, data.skin, matrices,
                            skinned.positions, skinned.normals);
        scene_.deformMesh(skinned.mesh, skinned.positions, skinned.normals);
        for (SkinnedLevel& level : skinned.levels) {
            level.positions.resize(level.vertices.size());
            level.normals.resize(level.vertices.size());
            for (std::size_t v = 0; v < level.vertices.size(); ++v) {
                level.positions[v] = skinned.positions[level.vertices[v]];
                level.normals[v] = skinned.normals[level.vertices[v]];
            }
            scene_.deformMesh(level.mesh, level.positions, level.normals);
        }
        skinned.poseRevision = component.poseRevision();
    }
    // The user's material per drawn slot: Materials names the file's slots.
    std::vector<std::string> materialNames;
    for (const std::uint32_t fileSlot : skinned.fileSlots)
        materialNames.push_back(fileSlot < component.Materials.size() ? component.Materials[fileSlot]
                                                                      : std::string());
    // Not seen by the irradiance probes: a character changes shape every frame
    // (Instance::affectIndirectLighting).
    placeInstance(component, skinned.mesh, materialNames, skinned.importedMaterials, skinned.importedNames,
                  library,
                  /*affectIndirectLighting=*/false);
}

void RenderScene::addSkinnedLevels(SkinnedEntry& entry, const sp::render::MeshData& data) {
    // The levels keep only the vertices they use, copied bit for bit: found again in the full mesh by their
    // position, normal and uv, so that each level's vertices follow the full mesh's skinned ones.
    const std::shared_ptr<const sp::render::MeshLevels> levels =
        sp::render::sharedLods(sp::render::contentKey(data), data);
    using VertexKey = std::array<float, 8>;
    auto keyOf = [](const sp::render::MeshData& mesh, std::size_t v) {
        return VertexKey{mesh.positions[v].x(), mesh.positions[v].y(), mesh.positions[v].z(),
                         mesh.normals[v].x(),   mesh.normals[v].y(),   mesh.normals[v].z(),
                         mesh.uvs[v].x(),       mesh.uvs[v].y()};
    };
    std::map<VertexKey, std::uint32_t> index;
    for (std::size_t v = 0; v < data.positions.size(); ++v)
        index.emplace(keyOf(data, v), std::uint32_t(v));
    std::vector<sp::render::MeshLod> lods;
    for (const auto& [level, error] : *levels) {
        SkinnedLevel skinnedLevel;
        for (std::size_t v = 0; v < level.positions.size(); ++v) {
            const auto it = index.find(keyOf(level, v));
            if (it == index.end()) { // a vertex the simplifier made: this level cannot follow the skin
                logOnce("skinned-lods:" + data.name, "RenderSubsystem: skinned mesh '" + data.name +
                                                         "' is drawn without levels of detail");
                for (const SkinnedLevel& made : entry.levels)
                    scene_.removeMesh(made.mesh);
                entry.levels.clear();
                return;
            }
            skinnedLevel.vertices.push_back(it->second);
        }
        skinnedLevel.mesh = scene_.addMesh(level);
        lods.push_back({skinnedLevel.mesh, error});
        entry.levels.push_back(std::move(skinnedLevel));
    }
    if (!lods.empty())
        scene_.setMeshLods(entry.mesh, std::move(lods));
}

void RenderScene::removeSkinnedMesh(SkinnedEntry& entry) {
    if (!entry.asset)
        return;
    scene_.removeMesh(entry.mesh); // before its levels, which it names
    for (const SkinnedLevel& level : entry.levels)
        scene_.removeMesh(level.mesh);
    // Its materials are the file's, kept for every component that shows it (skinnedMaterialsFor()).
    entry.asset.reset();
}

const RenderScene::SkinnedMaterials&
RenderScene::skinnedMaterialsFor(const std::shared_ptr<const sp::animation::SkeletalMeshData>& asset,
                                 const std::string& fileName) {
    if (auto it = skinnedMaterials_.find(asset.get()); it != skinnedMaterials_.end())
        return it->second;
    SkinnedMaterials materials{
        asset, sp::render::addMaterialsToScene(scene_, asset->mesh.materials, /*shared=*/true), {}};
    for (std::size_t i = 0; i < materials.ids.size(); ++i) {
        sp::render::Material material = scene_.material(materials.ids[i]);
        material.id = nextMaterialValue_++;
        scene_.setMaterial(materials.ids[i], material);
        const std::string& name = asset->mesh.materials[i].name;
        materials.names.push_back(name.empty() ? fileName + "#" + std::to_string(i) : name);
    }
    return skinnedMaterials_.emplace(asset.get(), std::move(materials)).first->second;
}

void RenderScene::syncDebugLine(const USplineComponent& spline) {
    DebugLineEntry& entry = debugLines_[spline.GetHandle()];
    const FTransform transform = spline.GetComponentTransform();
    if (entry.instance.isSet() && entry.revision == spline.curveRevision() && entry.transform == transform &&
        entry.thickness == spline.DebugLineThickness && entry.color == spline.DebugLineColor)
        return; // unchanged: the curve is sampled only when it moved or changed
    // The curve through points a tenth of a metre apart (at most 10001), in world space.
    std::vector<Eigen::Vector3f> points;
    for (const Eigen::Vector3d& p : spline.worldPolyline(0.1, 10000))
        points.push_back(p.cast<float>());
    if (points.size() < 2 || spline.GetSplineLength() <= 1e-6) { // nothing to draw (yet)
        removeDebugLine(entry);
        entry = DebugLineEntry{};
        return;
    }
    sp::render::MeshData mesh = sp::render::primitives::tube(points, float(spline.DebugLineThickness / 2.0));
    sp::render::Material material;
    material.baseColor = Eigen::Vector4f(0.02f, 0.02f, 0.02f, 1.0f);
    material.emissive = rgb(spline.DebugLineColor);
    if (entry.instance.isSet()) {
        scene_.updateMesh(entry.mesh, std::move(mesh));
        scene_.setMaterial(entry.material, material);
    } else {
        entry.mesh = scene_.addMesh(std::move(mesh));
        entry.material = scene_.addMaterial(material);
        entry.id = nextObjectId_++;
        idInfo_[entry.id] = {spline.GetHandle(), 0, "DebugLine"};
        sp::render::Instance instance;
        instance.mesh = entry.mesh;
        instance.materials = {entry.material};
        instance.objectIds = {entry.id};
        instance.castShadows = false;
        entry.instance = scene_.addInstance(instance);
    }
    entry.revision = spline.curveRevision();
    entry.transform = transform;
    entry.thickness = spline.DebugLineThickness;
    entry.color = spline.DebugLineColor;
}

void RenderScene::removeDebugLine(DebugLineEntry& entry) {
    if (!entry.instance.isSet())
        return;
    scene_.removeInstance(entry.instance);
    scene_.removeMesh(entry.mesh);
    scene_.removeMaterial(entry.material);
    idInfo_.erase(entry.id);
}

const RenderScene::MeshEntry* RenderScene::meshFor(const std::string& name) {
    if (auto it = meshes_.find(name); it != meshes_.end())
        return &it->second;
    MeshEntry entry;
    if (auto shape = basicShape(name)) { // the same in every world: uploaded once per renderer
        entry.mesh = scene_.addMesh(std::move(*shape), "shape:" + name);
        std::vector<sp::render::MeshLod> lods;
        for (ShapeLevel& level : basicShapeLods(name))
            lods.push_back({scene_.addMesh(std::move(level.data),
                                           "shape:" + name + "@lod" + std::to_string(lods.size())),
                            level.relativeError, level.surfaceError});
        scene_.setMeshLods(entry.mesh, std::move(lods));
    } else {
        try {
            const sp::render::ImportedMesh imported = sp::render::importMesh(name);
            const sp::render::ImportedMeshIds ids = sp::render::addToScene(scene_, imported, /*shared=*/true);
            entry.mesh = ids.mesh;
            entry.importedMaterials = ids.materials;
            for (std::size_t i = 0; i < imported.materials.size(); ++i) {
                const std::string materialName = imported.materials[i].name.empty()
                                                     ? name + "#" + std::to_string(i)
                                                     : imported.materials[i].name;
                entry.importedNames.push_back(materialName);
                sp::render::Material material = scene_.material(ids.materials[i]);
                material.id = nextMaterialValue_++;
                scene_.setMaterial(ids.materials[i], material);
                materials_.emplace(name + "#" + std::to_string(i),
                                   MaterialEntry{ids.materials[i], {}, material.id});
            }
        } catch (const sp::Error& error) {
            logOnce("mesh:" + name,
                    std::string("RenderSubsystem: mesh '") + name + "' is not rendered: " + error.what());
            return nullptr;
        }
    }
    return &meshes_.emplace(name, std::move(entry)).first->second;
}

std::optional<sp::render::TextureId>
RenderScene::cachedTexture(const std::string& key, const std::string& shown,
                           sp::render::TextureEncoding encoding,
                           const std::function<sp::render::TextureImage()>& load) {
    if (auto it = textures_.find(key); it != textures_.end())
        return it->second;
    try {
        sp::render::TextureImage image = load();
        // Keyed by its pixels and encoding, so that worlds loading the same image share its upload.
        std::string content = sp::render::contentKey(image, encoding);
        sp::render::TextureId id = scene_.addTexture(std::move(image), encoding, std::move(content));
        return textures_.emplace(key, id).first->second;
    } catch (const sp::Error& error) {
        logOnce("texture:" + key, "RenderSubsystem: texture '" + shown + "' is not used: " + error.what());
        return std::nullopt;
    }
}

std::optional<sp::render::TextureId> RenderScene::textureFor(const std::string& path,
                                                             sp::render::TextureEncoding encoding) {
    if (path.empty())
        return std::nullopt;
    return cachedTexture(path, path, encoding, [&] { return sp::render::TextureImage::load(path); });
}

std::optional<sp::render::TextureId>
RenderScene::occlusionRoughnessMetallicFor(const std::string& roughnessMetallic,
                                           const std::string& occlusion) {
    if (roughnessMetallic.empty() && occlusion.empty())
        return std::nullopt;
    return cachedTexture(
        "orm:" + roughnessMetallic + "\n" + occlusion,
        roughnessMetallic.empty() ? occlusion : roughnessMetallic, sp::render::TextureEncoding::Linear, [&] {
            std::optional<sp::render::TextureImage> maps[2];
            if (!roughnessMetallic.empty())
                maps[0] = sp::render::TextureImage::load(roughnessMetallic);
            if (!occlusion.empty() && occlusion != roughnessMetallic)
                maps[1] = sp::render::TextureImage::load(occlusion);
            // An ORM map named as both is read once and is its own occlusion.
            const sp::render::TextureImage* occluding =
                maps[1] ? &*maps[1] : (!occlusion.empty() && maps[0] ? &*maps[0] : nullptr);
            return sp::render::packOcclusionRoughnessMetallic(maps[0] ? &*maps[0] : nullptr, occluding);
        });
}

sp::render::MaterialId RenderScene::materialFor(const std::string& rawName,
                                                const std::map<std::string, FMaterialDesc>& library) {
    const std::string name = rawName.empty() ? "Default" : rawName;
    FMaterialDesc desc;
    if (auto it = library.find(name); it != library.end()) {
        desc = it->second;
    } else if (const FMaterialDesc* builtin = builtinMaterial(name)) {
        desc = *builtin;
    } else {
        logOnce("material:" + name,
                "RenderSubsystem: material '" + name +
                    "' is neither in an AMaterialLibrary nor built in; using the default");
        desc = *builtinMaterial("Default");
    }
    auto it = materials_.find(name);
    if (it != materials_.end() && it->second.desc == desc)
        return it->second.id;

    sp::render::Material material;
    material.baseColor = {desc.BaseColor.R, desc.BaseColor.G, desc.BaseColor.B, 1.0f};
    material.roughness = desc.Roughness;
    material.metallic = desc.Metallic;
    material.ambientOcclusion = desc.AmbientOcclusion;
    material.emissive = rgb(desc.Emissive);
    material.baseColorTexture = textureFor(desc.BaseColorTexture, sp::render::TextureEncoding::Srgb);
    material.roughnessMetallicTexture =
        occlusionRoughnessMetallicFor(desc.RoughnessMetallicTexture, desc.OcclusionTexture);
    material.normalTexture = textureFor(desc.NormalTexture, sp::render::TextureEncoding::Linear);
    material.textureSize = desc.TextureSize;
    material.validate(("material '" + name + "'").c_str());
    if (it != materials_.end()) { // changed: same handle and material id, new parameters
        material.id = it->second.value;
        scene_.setMaterial(it->second.id, material);
        it->second.desc = desc;
        return it->second.id;
    }
    material.id = nextMaterialValue_++;
    sp::render::MaterialId id = scene_.addMaterial(material);
    materials_.emplace(name, MaterialEntry{id, desc, material.id});
    return id;
}

std::optional<RenderScene::ObjectIdInfo> RenderScene::objectIdInfo(std::uint32_t id) const {
    auto it = idInfo_.find(id);
    if (it == idInfo_.end())
        return std::nullopt;
    return it->second;
}

std::uint32_t RenderScene::objectId(sp::reflect::ObjectHandle component, int slot) const {
    auto it = instances_.find(component);
    if (it == instances_.end() || slot < 0 || std::size_t(slot) >= it->second.ids.size())
        return 0;
    return it->second.ids[std::size_t(slot)];
}

std::uint32_t RenderScene::materialId(const std::string& name) const {
    auto it = materials_.find(name.empty() ? "Default" : name);
    return it == materials_.end() ? 0 : it->second.value;
}

} // namespace sp::sensors
