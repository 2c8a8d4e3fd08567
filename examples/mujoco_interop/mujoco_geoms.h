#pragma once
// How MuJoCo geoms become spear components (not reflected: mujoco_scene.cpp's helper).

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>

class AMujocoBody;
class AMaterialLibrary;

namespace mujoco_interop {

// What one model's geoms are turned into: materials go to `library` under "<prefix>/<geom>", meshes are
// written as OBJ files into `meshDir` (created on first use).
struct GeomContext {
    const mjModel* model = nullptr;
    AMaterialLibrary* library = nullptr;
    std::string prefix;
    std::filesystem::path meshDir;
};

// The name MuJoCo gives object `id` of `type`, or "<fallback>_<id>" when it has none.
std::string objectName(const mjModel* model, mjtObj type, int id, const char* fallback);

// Adds the components that show geom `geom` to `body` (one component named after the geom; a capsule is a
// scene component with a cylinder and two spheres under it), placed relative to the body frame. Returns
// false for a geom type spear cannot show (a height field), which gets no component.
bool addGeomComponents(const GeomContext& context, int geom, AMujocoBody& body);

} // namespace mujoco_interop
