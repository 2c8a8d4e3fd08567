// RenderScene's drawn roads: the surface and markings sp::zonegraph builds over an AZoneGraphData's lanes,
// one mesh of three slots (road, sidewalk, markings), made again when the lane graph is rebuilt.

#include "core/base/error.h"
#include "core/gameplay/zone_graph.h"
#include "core/sensors/render_scene.h"
#include "core/zonegraph/road_surface.h"

namespace sp::sensors {

namespace {

sp::render::MeshData meshOf(const sp::zonegraph::RoadSurface& surface, const std::string& name) {
    sp::render::MeshData mesh;
    mesh.name = name;
    for (const sp::zonegraph::SurfaceMesh* part : {&surface.road, &surface.sidewalk, &surface.markings}) {
        const std::uint32_t base = std::uint32_t(mesh.positions.size());
        mesh.submeshes.push_back({std::uint32_t(mesh.indices.size()), std::uint32_t(part->indices.size())});
        mesh.positions.insert(mesh.positions.end(), part->positions.begin(), part->positions.end());
        for (const std::uint32_t index : part->indices)
            mesh.indices.push_back(base + index);
    }
    mesh.normals.assign(mesh.positions.size(), Eigen::Vector3f::UnitZ());
    return mesh;
}

} // namespace

void RenderScene::syncRoads(AZoneGraphData& data, const std::map<std::string, FMaterialDesc>& library) {
    RoadEntry& entry = roads_[data.GetHandle()];
    const sp::zonegraph::LaneGraph* graph = nullptr;
    try {
        graph = &data.graph("RenderSubsystem (drawing the roads)");
    } catch (const sp::Error& e) {
        // Roads that make no lanes (two crossing without a junction) draw as they last did; the queries say
        // why.
        logOnce(std::string("roads:") + e.what(), e.what());
        return;
    }
    const std::vector<std::string> names{data.RoadMaterial, data.SidewalkMaterial, data.MarkingMaterial};
    if (!entry.instance.isSet() || entry.revision != data.graphRevision()) {
        sp::render::MeshData mesh =
            meshOf(sp::zonegraph::buildRoadSurface(*graph), "roads:" + data.GetName());
        if (mesh.indices.empty()) { // no lanes: nothing to draw
            removeRoads(entry);
            entry = RoadEntry{};
            return;
        }
        if (entry.instance.isSet()) {
            scene_.updateMesh(entry.mesh, std::move(mesh));
        } else {
            entry.mesh = scene_.addMesh(std::move(mesh));
            entry.firstId = nextObjectId_;
            nextObjectId_ += 3;
            sp::render::Instance instance;
            instance.mesh = entry.mesh;
            instance.objectIds = {entry.firstId, entry.firstId + 1, entry.firstId + 2};
            for (const std::string& name : names)
                instance.materials.push_back(materialFor(name, library));
            instance.castShadows = false; // flat on the ground: it would only shadow itself
            entry.instance = scene_.addInstance(instance);
        }
        entry.revision = data.graphRevision();
    }
    // The slots' materials by name, as a library has them now.
    sp::render::Instance instance = scene_.instance(entry.instance);
    std::vector<sp::render::MaterialId> materials;
    for (const std::string& name : names)
        materials.push_back(materialFor(name, library));
    if (materials != instance.materials) {
        instance.materials = std::move(materials);
        scene_.setInstance(entry.instance, instance);
    }
    for (int slot = 0; slot < 3; ++slot)
        idInfo_[entry.firstId + std::uint32_t(slot)] = {data.GetHandle(), slot, names[size_t(slot)]};
}

void RenderScene::removeRoads(RoadEntry& entry) {
    if (!entry.instance.isSet())
        return;
    scene_.removeInstance(entry.instance);
    scene_.removeMesh(entry.mesh);
    for (std::uint32_t slot = 0; slot < 3; ++slot)
        idInfo_.erase(entry.firstId + slot);
}

} // namespace sp::sensors
