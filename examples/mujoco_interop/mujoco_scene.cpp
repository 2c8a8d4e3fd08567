#include "mujoco_scene.h"

#include <mujoco/mujoco.h>

#include <unistd.h>

#include <atomic>
#include <cstring>
#include <filesystem>

#include "core/base/error.h"
#include "core/base/log.h"
#include "core/sensors/material_library.h"
#include "core/world/world.h"
#include "mujoco_geoms.h"

namespace {

// MuJoCo reports fatal errors through mju_error, which would end the process: make them engine errors
// (the engine keeps running), and send its warnings to the log instead of MUJOCO_LOG.TXT.
void throwMujocoError(const char* message) {
    SP_THROW(sp::InvalidState, "MuJoCo error: ", message);
}
void logMujocoWarning(const char* message) {
    SP_LOG("MuJoCo warning: ", message);
}

// A directory of its own for each model's mesh files (the renderer caches meshes by path).
std::filesystem::path newMeshDir() {
    static std::atomic<int> counter{0};
    return std::filesystem::temp_directory_path() /
           ("spear_mujoco_" + std::to_string(getpid()) + "_" + std::to_string(counter++));
}

} // namespace

struct AMujocoScene::Model {
    mjModel* model = nullptr;
    mjData* data = nullptr;
    std::vector<std::string> bodyNames;
    std::vector<sp::reflect::ObjectHandle> bodyActors; // by body id
    std::vector<int> movingBodies;                     // ids of the bodies Step() moves
    std::filesystem::path meshDir;

    ~Model() {
        mj_deleteData(data);
        mj_deleteModel(model);
        std::error_code ignored;
        std::filesystem::remove_all(meshDir, ignored);
    }

    // The actor of body `body`; throws StaleObject naming the body when it was destroyed.
    AMujocoBody& actor(int body, std::string_view function) const {
        auto* found = dynamic_cast<AMujocoBody*>(sp::reflect::ObjectTable::find(bodyActors[size_t(body)]));
        SP_CHECK(found, sp::StaleObject, function, ": the actor of body '", bodyNames[size_t(body)],
                 "' was destroyed (LoadMjcf again to respawn the bodies)");
        return *found;
    }
};

AMujocoScene::AMujocoScene() = default;
AMujocoScene::~AMujocoScene() = default;

AMujocoScene::Model& AMujocoScene::model(const char* function) const {
    SP_CHECK(model_, sp::InvalidState, function, ": no model is loaded (call LoadMjcf first)");
    return *model_;
}

void AMujocoScene::LoadMjcf(const std::string& Path) {
    const std::string function = "AMujocoScene.LoadMjcf()";
    SP_CHECK(std::filesystem::is_regular_file(Path), sp::NotFound, function, ": no MJCF file '", Path, "'");
    load(function, Path, nullptr);
}

void AMujocoScene::LoadMjcfString(const std::string& Xml) {
    load("AMujocoScene.LoadMjcfString()", "<string>", &Xml);
}

void AMujocoScene::load(const std::string& function, const std::string& path, const std::string* xml) {
    UWorld* world = GetWorld();
    SP_CHECK(world, sp::InvalidState, function, ": the scene is not in a world");
    mju_user_error = throwMujocoError;
    mju_user_warning = logMujocoWarning;

    // Compile first: a model that does not compile leaves the scene as it was.
    char error[1024] = "";
    mjModel* compiled = nullptr;
    if (xml) {
        mjVFS vfs;
        mj_defaultVFS(&vfs);
        SP_CHECK(mj_makeEmptyFileVFS(&vfs, "model.xml", int(xml->size())) == 0, sp::InvalidState, function,
                 ": cannot make MuJoCo's in-memory file");
        std::memcpy(vfs.filedata[vfs.nfile - 1], xml->data(), xml->size());
        compiled = mj_loadXML("model.xml", &vfs, error, sizeof error);
        mj_deleteVFS(&vfs);
    } else {
        compiled = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    }
    SP_CHECK(compiled, sp::InvalidArgument, function, ": MuJoCo cannot load '", path, "': ", error);

    Clear();
    model_ = std::make_unique<Model>();
    model_->model = compiled;
    model_->data = mj_makeData(compiled);
    model_->meshDir = newMeshDir();
    mj_forward(compiled, model_->data);
    try {
        spawnBodies(function, *world);
    } catch (...) { // no half-spawned model: its actors go
        Clear();
        throw;
    }
    ModelPath = path;
    NumBodies = compiled->nbody;
    NumGeoms = compiled->ngeom;
}

void AMujocoScene::spawnBodies(const std::string& function, UWorld& world) {
    Model& m = *model_;
    const mjModel* model = m.model;
    AMaterialLibrary* library = nullptr;
    for (AActor* actor : world.find_actors())
        if ((library = dynamic_cast<AMaterialLibrary*>(actor)))
            break;
    if (!library)
        library = static_cast<AMaterialLibrary*>(world.spawn_actor(&AMaterialLibrary::StaticClass()));
    const mujoco_interop::GeomContext context{model, library, GetName(), m.meshDir};

    // One actor per body, in MuJoCo's order, with the body's geoms as its components.
    std::vector<std::vector<int>> geomsOfBody(size_t(model->nbody));
    for (int geom = 0; geom < model->ngeom; ++geom)
        geomsOfBody[size_t(model->geom_bodyid[geom])].push_back(geom);
    for (int body = 0; body < model->nbody; ++body) {
        const std::string name =
            body == 0 ? "world" : mujoco_interop::objectName(model, mjOBJ_BODY, body, "body");
        // Welded to the world and not a mocap body: never moves.
        const bool isStatic = model->body_weldid[body] == 0 && model->body_mocapid[body] < 0;
        auto* actor =
            static_cast<AMujocoBody*>(world.spawn_actor(&AMujocoBody::StaticClass(), FVector(), FRotator(),
                                                        GetName() + "/" + name, {"mujoco", GetName()}));
        m.bodyNames.push_back(name);
        m.bodyActors.push_back(actor->GetHandle());
        actor->BodyName = name;
        actor->BodyId = body;
        actor->bStaticBody = isStatic;
        actor->NumGeoms = int32_t(geomsOfBody[size_t(body)].size());
        const mjtNum* pos = m.data->xpos + 3 * body;
        const mjtNum* quat = m.data->xquat + 4 * body;
        actor->Body->SetRelativeTransform(
            {{pos[0], pos[1], pos[2]}, {quat[1], quat[2], quat[3], quat[0]}, {1, 1, 1}});
        for (int geom : geomsOfBody[size_t(body)])
            if (!mujoco_interop::addGeomComponents(context, geom, *actor))
                SP_LOG(function, ": geom '", mujoco_interop::objectName(model, mjOBJ_GEOM, geom, "geom"),
                       "' of body '", name, "' is a height field, which spear does not show");
        if (isStatic) {
            for (const auto& component : actor->GetComponentList())
                if (auto* scene = dynamic_cast<USceneComponent*>(component.get()))
                    scene->SetMobility(EComponentMobility::Static);
        } else {
            m.movingBodies.push_back(body);
        }
    }
}

void AMujocoScene::Clear() {
    if (!model_)
        return;
    if (UWorld* world = GetWorld())
        for (const auto& handle : model_->bodyActors)
            if (auto* actor = dynamic_cast<AActor*>(sp::reflect::ObjectTable::find(handle)))
                world->destroy_actor(actor);
    model_.reset();
    ModelPath.clear();
    NumBodies = NumGeoms = 0;
}

void AMujocoScene::Step(int32_t NumSteps) {
    const char* function = "AMujocoScene.Step()";
    Model& m = model(function);
    SP_CHECK(NumSteps >= 0, sp::InvalidArgument, function, ": NumSteps must be >= 0, got ", NumSteps);
    // Every actor is checked before MuJoCo moves, so that a failed call changes nothing.
    std::vector<USceneComponent*> roots;
    roots.reserve(m.movingBodies.size());
    for (int body : m.movingBodies)
        roots.push_back(m.actor(body, function).Body);
    for (int32_t step = 0; step < NumSteps; ++step)
        mj_step(m.model, m.data);
    // mj_step leaves xpos/xquat at the state before its last integration: bring them to the state reached.
    mj_kinematics(m.model, m.data);
    for (size_t i = 0; i < roots.size(); ++i) {
        const mjtNum* pos = m.data->xpos + 3 * m.movingBodies[i];
        const mjtNum* quat = m.data->xquat + 4 * m.movingBodies[i];
        roots[i]->SetRelativeTransform(
            {{pos[0], pos[1], pos[2]}, {quat[1], quat[2], quat[3], quat[0]}, {1, 1, 1}});
    }
}

void AMujocoScene::SetForces(const sp::reflect::SpArray<double>& Forces) {
    const char* function = "AMujocoScene.SetForces()";
    Model& m = model(function);
    const auto& shape = Forces.getShape();
    const int64_t bodies = m.model->nbody;
    SP_CHECK(shape.size() == 2 && shape[0] == bodies && (shape[1] == 3 || shape[1] == 6), sp::InvalidArgument,
             function, ": array 'Forces' must have shape (", bodies, ", 3) or (", bodies,
             ", 6) (one row per body, the world first), got ", Forces.describeShape());
    const auto values = Forces.getView();
    const int64_t columns = shape[1];
    for (int64_t body = 0; body < bodies; ++body)
        for (int64_t k = 0; k < 6; ++k)
            m.data->xfrc_applied[6 * body + k] = k < columns ? values[size_t(body * columns + k)] : 0.0;
}

FMujocoBodyPoses AMujocoScene::GetBodyPoses() const {
    const Model& m = model("AMujocoScene.GetBodyPoses()");
    const int bodies = m.model->nbody;
    FMujocoBodyPoses poses;
    poses.Positions.setDataSource(std::vector<double>(m.data->xpos, m.data->xpos + 3 * bodies), {-1, 3});
    poses.Quaternions.setDataSource(std::vector<double>(m.data->xquat, m.data->xquat + 4 * bodies), {-1, 4});
    return poses;
}

std::vector<std::string> AMujocoScene::GetBodyNames() const {
    return model("AMujocoScene.GetBodyNames()").bodyNames;
}

std::vector<AMujocoBody*> AMujocoScene::GetBodyActors() const {
    const char* function = "AMujocoScene.GetBodyActors()";
    const Model& m = model(function);
    std::vector<AMujocoBody*> actors;
    for (int body = 0; body < int(m.bodyActors.size()); ++body)
        actors.push_back(&m.actor(body, function));
    return actors;
}

AMujocoBody* AMujocoScene::GetBodyActor(const std::string& BodyName) const {
    const char* function = "AMujocoScene.GetBodyActor()";
    const Model& m = model(function);
    for (size_t body = 0; body < m.bodyNames.size(); ++body)
        if (m.bodyNames[body] == BodyName)
            return &m.actor(int(body), function);
    SP_THROW(sp::NotFound, function, ": the model has no body named '", BodyName, "'");
}

double AMujocoScene::GetSimTime() const {
    return model("AMujocoScene.GetSimTime()").data->time;
}

double AMujocoScene::GetTimestep() const {
    return model("AMujocoScene.GetTimestep()").model->opt.timestep;
}
