#pragma once
// AMujocoScene: MuJoCo steps the dynamics, spear renders. LoadMjcf() compiles an MJCF model and spawns one
// AMujocoBody per body, with a mesh component per geom (box, sphere, ellipsoid, cylinder, plane, mesh, and
// a capsule as a cylinder and two spheres); Step() steps MuJoCo and writes every moving body's pose into
// its actor in the same call. spear's own physics never simulates these components (they are kinematic or
// static collision bodies, so traces hit them): MuJoCo owns their dynamics.
//
// Conventions: MuJoCo's world frame is spear's (right-handed, Z up, metres); a MuJoCo quaternion
// (w, x, y, z) is the FQuat {X=x, Y=y, Z=z, W=w}.

#include <memory>
#include <string>
#include <vector>

#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "mujoco_body.h"

/// MuJoCo's pose of every body after the last step (body 0 is the world).
SPSTRUCT(TypedDict)
struct FMujocoBodyPoses {
    SP_GENERATED_BODY()

    /// Body positions (MuJoCo's xpos) in metres, (nbody, 3) float64.
    SPPROPERTY()
    sp::reflect::SpArray<double> Positions;

    /// Body orientations (MuJoCo's xquat) as (w, x, y, z), (nbody, 4) float64.
    SPPROPERTY()
    sp::reflect::SpArray<double> Quaternions;
};

/// A MuJoCo model stepped by MuJoCo and shown by spear actors, one AMujocoBody per body.
SPCLASS()
class AMujocoScene : public AActor {
    SP_GENERATED_BODY()
  public:
    AMujocoScene();
    ~AMujocoScene() override;

    /// The MJCF file of the loaded model ("<string>" when it came from LoadMjcfString, "" when none).
    SPPROPERTY(VisibleAnywhere)
    std::string ModelPath;

    /// The number of bodies of the loaded model, the world body included (0 when none is loaded).
    SPPROPERTY(VisibleAnywhere)
    int32_t NumBodies = 0;

    /// The number of geoms of the loaded model.
    SPPROPERTY(VisibleAnywhere)
    int32_t NumGeoms = 0;

    /// Loads the MJCF file at Path (replacing any model loaded before) and spawns its bodies' actors.
    SPFUNCTION()
    void LoadMjcf(const std::string& Path);

    /// Loads a model from MJCF text (assets are found relative to the working directory).
    SPFUNCTION()
    void LoadMjcfString(const std::string& Xml);

    /// Destroys the bodies' actors and frees the model (LoadMjcf does it first; destroying the scene does
    /// not).
    SPFUNCTION()
    void Clear();

    /// Advances MuJoCo by NumSteps steps of its timestep, then moves every moving body's actor to its pose.
    SPFUNCTION()
    void Step(int32_t NumSteps = 1);

    /// Sets the force (and torque) on each body's centre of mass, held until the next call: an (nbody, 3)
    /// float64 array of forces in newtons or an (nbody, 6) one of forces and torques (N m), row 0 the world.
    SPFUNCTION()
    void SetForces(const sp::reflect::SpArray<double>& Forces);

    /// Returns MuJoCo's position and orientation of every body (what the bodies' actors show).
    SPFUNCTION()
    FMujocoBodyPoses GetBodyPoses() const;

    /// Returns the names of the bodies in MuJoCo's order (row i of GetBodyPoses() is body i).
    SPFUNCTION()
    std::vector<std::string> GetBodyNames() const;

    /// Returns the actors of the bodies, in MuJoCo's order.
    SPFUNCTION()
    std::vector<AMujocoBody*> GetBodyActors() const;

    /// Returns the actor of the body called BodyName.
    SPFUNCTION(NotNull)
    AMujocoBody* GetBodyActor(const std::string& BodyName) const;

    /// Returns MuJoCo's simulated time in seconds.
    SPFUNCTION()
    double GetSimTime() const;

    /// Returns MuJoCo's timestep in seconds (the model's <option timestep>).
    SPFUNCTION()
    double GetTimestep() const;

  private:
    struct Model; // MuJoCo's model and data, and the bodies' actors (mujoco_scene.cpp)
    void load(const std::string& function, const std::string& path, const std::string* xml);
    void spawnBodies(const std::string& function, UWorld& world);
    Model& model(const char* function) const;
    std::unique_ptr<Model> model_;
};
