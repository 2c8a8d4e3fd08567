#include "core/world/static_mesh_component.h"

#include <array>
#include <filesystem>
#include <string_view>

#include "core/base/asset_path.h"
#include "core/base/error.h"
#include "core/world/mesh_geometry.h"

namespace {
// Built-in shapes, unit sized like UE's BasicShapes but in metres, centred on the origin.
struct BasicShape {
    std::string_view name;
    Eigen::Vector3d halfExtent;
    ECollisionPrimitive collision;
};
constexpr std::string_view kBasicShapesPrefix = "/Engine/BasicShapes/";
const std::array<BasicShape, 4> kBasicShapes{{{"Cube", {0.5, 0.5, 0.5}, ECollisionPrimitive::Box},
                                              {"Sphere", {0.5, 0.5, 0.5}, ECollisionPrimitive::Sphere},
                                              {"Cylinder", {0.5, 0.5, 0.5}, ECollisionPrimitive::Cylinder},
                                              {"Plane", {0.5, 0.5, 0.0}, ECollisionPrimitive::Plane}}};

const BasicShape* findBasicShape(std::string_view mesh) {
    if (!mesh.starts_with(kBasicShapesPrefix))
        return nullptr;
    mesh.remove_prefix(kBasicShapesPrefix.size());
    for (const auto& shape : kBasicShapes)
        if (shape.name == mesh)
            return &shape;
    return nullptr;
}

// "/Engine/BasicShapes/Cube, /Engine/BasicShapes/Sphere, ...", for messages.
std::string basicShapeNames() {
    std::string names;
    for (const auto& shape : kBasicShapes)
        names += (names.empty() ? "" : ", ") + std::string(kBasicShapesPrefix) + std::string(shape.name);
    return names;
}

// The folder of the scene file this thread is loading (UStaticMeshComponent::SceneFolderScope), or "".
thread_local std::string tSceneFolder;

// `name` in the loading scene's folder when it is a relative name of a file there, else "".
std::string inSceneFolder(const std::string& name) {
    const std::filesystem::path path(name);
    if (tSceneFolder.empty() || path.is_absolute())
        return "";
    std::error_code error;
    const std::filesystem::path candidate = (std::filesystem::path(tSceneFolder) / path).lexically_normal();
    return std::filesystem::is_regular_file(candidate, error) ? candidate.string() : "";
}

// Where a relative file name is looked for (sp::findAsset, after the loading scene's folder), for messages.
std::string searchedFolders(const std::string& name) {
    if (std::filesystem::path(name).is_absolute())
        return "";
    std::string folders = tSceneFolder.empty() ? "" : "the scene's folder " + tSceneFolder + ", ";
    folders += "the working directory";
    for (const std::string& folder : sp::assetSearchPath())
        folders += ", " + folder;
    return " (looked for in " + folders + ")";
}
} // namespace

UStaticMeshComponent::SceneFolderScope::SceneFolderScope(std::string folder)
    : previous_(std::move(tSceneFolder)) {
    tSceneFolder = std::move(folder);
}

UStaticMeshComponent::SceneFolderScope::~SceneFolderScope() {
    tSceneFolder = std::move(previous_);
}

bool UStaticMeshComponent::SetStaticMesh(const std::string& NewMesh) {
    constexpr std::string_view kFunction = "UStaticMeshComponent.SetStaticMesh()";
    std::string file; // the file in the loading scene's folder, if it is there
    if (!NewMesh.empty() && !findBasicShape(NewMesh)) {
        SP_CHECK(sp::world::isMeshFile(NewMesh), sp::NotFound, kFunction, ": '", NewMesh,
                 "' is not a built-in shape (", basicShapeNames(), ")");
        file = inSceneFolder(NewMesh);
        try {
            // Found as importMesh() finds every asset; loaded now, once, for bounds and physics.
            sp::world::loadMeshGeometry(file.empty() ? NewMesh : file, kFunction);
        } catch (const sp::NotFound&) {
            SP_THROW(sp::NotFound, kFunction, ": mesh file '", NewMesh, "' not found",
                     searchedFolders(NewMesh));
        }
    }
    StaticMesh = NewMesh;
    resolvedName_ = file.empty() ? std::string() : NewMesh;
    resolvedFile_ = std::move(file);
    return true;
}

void UStaticMeshComponent::SetMaterial(int ElementIndex, const std::string& Material) {
    sp::world::setMaterialSlot(Materials, ElementIndex, Material, "UStaticMeshComponent.SetMaterial()");
}

const std::string& UStaticMeshComponent::GetMeshAsset() const {
    return !resolvedFile_.empty() && resolvedName_ == StaticMesh ? resolvedFile_ : StaticMesh;
}

Eigen::AlignedBox3d UStaticMeshComponent::GetLocalBounds() const {
    if (sp::world::isMeshFile(StaticMesh)) {
        const auto geometry = sp::world::findMeshGeometry(GetMeshAsset());
        return geometry ? geometry->bounds : Eigen::AlignedBox3d{};
    }
    const BasicShape* shape = findBasicShape(StaticMesh);
    if (!shape)
        return {};
    return {-shape->halfExtent, shape->halfExtent};
}

ECollisionPrimitive UStaticMeshComponent::GetMeshCollisionPrimitive() const {
    // A mesh file simulates as its convex hull (Bullet needs a convex shape for a dynamic body) and
    // otherwise, static or kinematic, collides as its triangles, which also suits flat meshes.
    if (sp::world::isMeshFile(StaticMesh))
        return bSimulatePhysics ? ECollisionPrimitive::ConvexHull : ECollisionPrimitive::TriangleMesh;
    const BasicShape* shape = findBasicShape(StaticMesh);
    return shape ? shape->collision : ECollisionPrimitive::NoCollision;
}
