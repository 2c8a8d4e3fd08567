#include "core/world/mesh_geometry.h"

#include <map>
#include <mutex>

#include "core/base/error.h"
#include "core/render/mesh_import.h"

namespace sp::world {

namespace {
std::mutex gMutex;
std::map<std::string, std::shared_ptr<const MeshGeometry>, std::less<>> gCache;
} // namespace

bool isMeshFile(std::string_view mesh) {
    return !mesh.empty() && !mesh.starts_with("/Engine/");
}

std::shared_ptr<const MeshGeometry> loadMeshGeometry(const std::string& path, std::string_view function) {
    {
        std::lock_guard lock(gMutex);
        if (auto it = gCache.find(path); it != gCache.end())
            return it->second;
    }
    render::ImportedMesh imported;
    try {
        imported = render::importMesh(path);
    } catch (const NotFound& error) {
        SP_THROW(NotFound, function, ": mesh file '", path, "' not found");
    } catch (const InvalidArgument& error) {
        SP_THROW(InvalidArgument, function, ": mesh file '", path, "' cannot be read: ", error.what());
    }
    auto geometry = std::make_shared<MeshGeometry>();
    geometry->vertices.reserve(imported.mesh.positions.size());
    for (const Eigen::Vector3f& p : imported.mesh.positions) {
        geometry->vertices.push_back(p.cast<double>());
        geometry->bounds.extend(p.cast<double>());
    }
    geometry->indices = imported.mesh.indices;
    std::lock_guard lock(gMutex);
    return gCache.emplace(path, std::move(geometry)).first->second;
}

std::shared_ptr<const MeshGeometry> findMeshGeometry(const std::string& path) {
    try {
        return loadMeshGeometry(path, "findMeshGeometry()");
    } catch (const Error&) {
        return nullptr;
    }
}

} // namespace sp::world
