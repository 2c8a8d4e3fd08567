#include "mujoco_geoms.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <fstream>

#include "core/base/error.h"
#include "core/sensors/material_library.h"
#include "core/world/static_mesh_component.h"
#include "mujoco_body.h"

namespace mujoco_interop {
namespace {

// An infinite MuJoCo plane (size 0) is drawn this far from its centre in spear, like MuJoCo's own renderer,
// which draws a finite patch of it too.
constexpr double kInfinitePlaneHalfSize = 50.0;
// MuJoCo draws geoms of groups 0, 1 and 2 by default (higher groups usually hold collision-only geoms).
constexpr int kFirstHiddenGroup = 3;

const char* basicShape(int type) {
    switch (type) {
    case mjGEOM_PLANE:
        return "/Engine/BasicShapes/Plane";
    case mjGEOM_SPHERE:
    case mjGEOM_ELLIPSOID:
        return "/Engine/BasicShapes/Sphere";
    case mjGEOM_CYLINDER:
    case mjGEOM_CAPSULE:
        return "/Engine/BasicShapes/Cylinder";
    case mjGEOM_BOX:
        return "/Engine/BasicShapes/Cube";
    default:
        return nullptr;
    }
}

// The unit basic shapes are 1 m across (half extent 0.5): a geom of MuJoCo size s scales them by 2 s.
FVector meshScale(int type, const mjtNum* size) {
    switch (type) {
    case mjGEOM_PLANE: {
        const double hx = size[0] > 0 ? size[0] : kInfinitePlaneHalfSize;
        const double hy = size[1] > 0 ? size[1] : kInfinitePlaneHalfSize;
        return {2 * hx, 2 * hy, 1.0};
    }
    case mjGEOM_SPHERE:
        return {2 * size[0], 2 * size[0], 2 * size[0]};
    case mjGEOM_CYLINDER:
    case mjGEOM_CAPSULE: // the capsule's cylinder part; its caps are spheres of the same radius
        return {2 * size[0], 2 * size[0], 2 * size[1]};
    case mjGEOM_ELLIPSOID:
    case mjGEOM_BOX:
        return {2 * size[0], 2 * size[1], 2 * size[2]};
    default: // meshes are written in metres
        return {1.0, 1.0, 1.0};
    }
}

// Writes mesh `mesh` as an OBJ file with one normal per face (so that it is shaded flat, as MuJoCo shades
// it), in the mesh frame MuJoCo compiled it to (centred and aligned with its inertia; the geom's pose
// accounts for that). Returns the file's path; a mesh several geoms share is written once.
std::string writeMeshObj(const GeomContext& context, int mesh) {
    const mjModel* model = context.model;
    std::filesystem::create_directories(context.meshDir);
    const std::filesystem::path path =
        context.meshDir / (std::to_string(mesh) + "_" + objectName(model, mjOBJ_MESH, mesh, "mesh") + ".obj");
    if (std::filesystem::exists(path))
        return path.string();
    std::ofstream out(path);
    SP_CHECK(out, sp::InvalidState, "AMujocoScene: cannot write the mesh file '", path.string(), "'");
    const float* vertices = model->mesh_vert + 3 * model->mesh_vertadr[mesh];
    const int* faces = model->mesh_face + 3 * model->mesh_faceadr[mesh];
    for (int f = 0; f < model->mesh_facenum[mesh]; ++f) {
        Eigen::Vector3d corner[3];
        for (int c = 0; c < 3; ++c) {
            const float* v = vertices + 3 * faces[3 * f + c];
            corner[c] = {v[0], v[1], v[2]};
            out << "v " << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
        }
        Eigen::Vector3d normal = (corner[1] - corner[0]).cross(corner[2] - corner[0]);
        normal = normal.norm() > 0 ? normal.normalized() : Eigen::Vector3d::UnitZ(); // a degenerate face
        out << "vn " << normal.x() << ' ' << normal.y() << ' ' << normal.z() << '\n';
        const int first = 3 * f + 1, n = f + 1;
        out << "f " << first << "//" << n << ' ' << first + 1 << "//" << n << ' ' << first + 2 << "//" << n
            << '\n';
    }
    SP_CHECK(out, sp::InvalidState, "AMujocoScene: cannot write the mesh file '", path.string(), "'");
    return path.string();
}

// The geom's colour as MuJoCo draws it: its material's when it has one and keeps the default rgba.
FMaterialDesc geomMaterial(const mjModel* model, int geom) {
    const float* rgba = model->geom_rgba + 4 * geom;
    const int material = model->geom_matid[geom];
    const bool defaultRgba = rgba[0] == 0.5f && rgba[1] == 0.5f && rgba[2] == 0.5f && rgba[3] == 1.0f;
    float roughness = 0.5f;
    if (material >= 0) {
        if (defaultRgba)
            rgba = model->mat_rgba + 4 * material;
        roughness = std::clamp(1.0f - model->mat_shininess[material], 0.05f, 1.0f);
    }
    FMaterialDesc desc;
    desc.BaseColor = {rgba[0], rgba[1], rgba[2], 1.0f};
    desc.Roughness = roughness;
    return desc;
}

UStaticMeshComponent& addMesh(AMujocoBody& body, const std::string& name, const std::string& mesh,
                              const std::string& material, bool visible) {
    auto* component = body.CreateDefaultSubobject<UStaticMeshComponent>(name);
    component->StaticMesh = mesh;
    component->SetMaterial(0, material);
    component->bVisible = visible;
    return *component;
}

} // namespace

std::string objectName(const mjModel* model, mjtObj type, int id, const char* fallback) {
    const char* name = mj_id2name(model, type, id);
    return name && *name ? std::string(name) : std::string(fallback) + "_" + std::to_string(id);
}

bool addGeomComponents(const GeomContext& context, int geom, AMujocoBody& body) {
    const mjModel* model = context.model;
    const int type = model->geom_type[geom];
    if (type != mjGEOM_MESH && !basicShape(type))
        return false;
    const std::string name = objectName(model, mjOBJ_GEOM, geom, "geom");
    const std::string material = context.prefix + "/" + name;
    context.library->SetMaterial(material, geomMaterial(model, geom));
    const bool visible = model->geom_group[geom] < kFirstHiddenGroup && model->geom_rgba[4 * geom + 3] > 0.0f;

    const mjtNum* pos = model->geom_pos + 3 * geom;
    const mjtNum* quat = model->geom_quat + 4 * geom; // w, x, y, z
    const mjtNum* size = model->geom_size + 3 * geom;
    FTransform placement{
        {pos[0], pos[1], pos[2]}, {quat[1], quat[2], quat[3], quat[0]}, meshScale(type, size)};

    if (type == mjGEOM_CAPSULE) {
        // spear has no capsule mesh: a cylinder of the capsule's length with a sphere on each end, under
        // one unscaled component at the geom's pose (so that the spheres stay round).
        auto* capsule = body.CreateDefaultSubobject<USceneComponent>(name);
        capsule->SetRelativeTransform({placement.Translation, placement.Rotation, {1.0, 1.0, 1.0}});
        const double radius = size[0], halfLength = size[1];
        const FVector ball{2 * radius, 2 * radius, 2 * radius};
        struct Part {
            const char* suffix;
            const char* mesh;
            FTransform transform;
        };
        const Part parts[] = {
            {"_cylinder", "/Engine/BasicShapes/Cylinder", {{}, {}, placement.Scale3D}},
            {"_cap_top", "/Engine/BasicShapes/Sphere", {{0.0, 0.0, halfLength}, {}, ball}},
            {"_cap_bottom", "/Engine/BasicShapes/Sphere", {{0.0, 0.0, -halfLength}, {}, ball}},
        };
        for (const Part& part : parts) {
            UStaticMeshComponent& mesh = addMesh(body, name + part.suffix, part.mesh, material, visible);
            mesh.AttachToComponent(capsule, false);
            mesh.SetRelativeTransform(part.transform);
        }
        return true;
    }
    const std::string mesh =
        type == mjGEOM_MESH ? writeMeshObj(context, model->geom_dataid[geom]) : basicShape(type);
    UStaticMeshComponent& component = addMesh(body, name, mesh, material, visible);
    component.SetRelativeTransform(placement);
    if (type == mjGEOM_ELLIPSOID) // spear's sphere collision shape takes a uniform scale only
        component.CollisionPrimitive = ECollisionPrimitive::Box;
    return true;
}

} // namespace mujoco_interop
