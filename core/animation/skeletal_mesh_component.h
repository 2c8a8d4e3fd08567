#pragma once
// USkeletalMeshComponent: a primitive that shows a skinned mesh posed by its skeleton, either by an animation
// clip playing (UE's single-node animation mode: PlayAnimation, Stop, SetPosition, SetPlayRate) or by a pose
// set from Python, bone transforms as one (bones, 4, 4) array. The renderer skins the mesh for the pose
// (every modality, shadows and the path tracer see the posed mesh); bones are sockets other components attach
// to (USceneComponent.AttachToComponent's SocketName).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/animation/skeletal_import.h"
#include "core/reflect/sp_array.h"
#include "core/world/actor.h"
#include "core/world/primitive_component.h"

/// The space a bone's transform is given in.
SPENUM()
enum class EBoneSpaces : uint8_t {
    /// The world's.
    WorldSpace = 0,
    /// The component's: what the bone is relative to the skeletal mesh component.
    ComponentSpace = 1,
};

/// A component that renders a skinned mesh, posed by an animation clip or by bone transforms.
SPCLASS()
class USkeletalMeshComponent : public UPrimitiveComponent {
    SP_GENERATED_BODY()
  public:
    /// The skeletal mesh asset: a skinned mesh file (glTF 2.0 skins; FBX where assimp reads it), found as
    /// every asset is ("/Game/characters/humanoid.glb" is the built-in humanoid). Setting it is
    /// SetSkeletalMesh().
    SPPROPERTY(Setter = SetSkeletalMesh)
    std::string SkeletalMesh;

    /// One material asset per mesh slot; an empty entry uses the file's own material for that slot.
    SPPROPERTY()
    std::vector<std::string> Materials;

    /// The clip played from the start of play and by Play(): one of the mesh file's clips ("walk"), or
    /// "<file>#<clip>" for a clip of another file made for the same skeleton. Empty: the bind pose.
    /// PlayAnimation() sets it.
    SPPROPERTY(Setter = SetAnimToPlay)
    std::string AnimToPlay;

    /// Whether the clip starts again from its beginning when it ends (else it holds its last pose and stops).
    SPPROPERTY()
    bool bLooping = true;

    /// Seconds of the clip per second of the world's time: 1 plays it as authored, negative backwards.
    SPPROPERTY(Setter = SetPlayRate)
    double PlayRate = 1.0;

    /// Sets the skeletal mesh asset. Returns true; raises NotFoundError naming the file when there is none,
    /// InvalidArgumentError when it cannot be read or has no skeleton. The pose becomes the bind pose, and
    /// the clip to play is looked up again in the new mesh's file.
    SPFUNCTION()
    bool SetSkeletalMesh(const std::string& NewMesh);

    /// Sets the material of one slot, growing the list as needed.
    SPFUNCTION()
    void SetMaterial(int ElementIndex, const std::string& Material);

    /// Returns the number of bones of the skeleton (0 without a mesh).
    SPFUNCTION()
    int GetNumBones() const;

    /// Returns the name of bone BoneIndex; raises InvalidArgumentError when there is no such bone.
    SPFUNCTION()
    std::string GetBoneName(int BoneIndex) const;

    /// Returns the index of the bone named BoneName, -1 when there is none (UE's INDEX_NONE).
    SPFUNCTION()
    int GetBoneIndex(const std::string& BoneName) const;

    /// Returns the transform of bone BoneName in the current pose, in Space; raises NotFoundError naming the
    /// bone when the skeleton has none of that name.
    SPFUNCTION()
    FTransform GetBoneTransform(const std::string& BoneName,
                                EBoneSpaces Space = EBoneSpaces::WorldSpace) const;

    /// Returns the world transform of socket InSocketName: a bone's (the component's own for an empty name);
    /// raises NotFoundError naming the socket when there is no such bone.
    FTransform GetSocketTransform(const std::string& InSocketName) const override;

    /// Returns true when InSocketName names a bone.
    bool DoesSocketExist(const std::string& InSocketName) const override;

    /// Returns the names of the clips of the mesh's file, in the file's order.
    SPFUNCTION()
    std::vector<std::string> GetAnimationNames() const;

    /// Plays NewAnimToPlay (a clip name, as AnimToPlay) from its start; raises NotFoundError naming the clip
    /// and those there are when there is no such clip, InvalidArgumentError when a file's clip is for another
    /// skeleton.
    SPFUNCTION()
    void PlayAnimation(const std::string& NewAnimToPlay, bool bLoop);

    /// Plays AnimToPlay from where it is (from its start when it had ended), looping when bLoop is true.
    SPFUNCTION()
    void Play(bool bLoop);

    /// Stops the clip where it is: the pose stays.
    SPFUNCTION()
    void Stop();

    /// Returns true while a clip plays.
    SPFUNCTION()
    bool IsPlaying() const { return playing_; }

    /// Moves the clip to InPos seconds (clamped to its length) and poses the mesh there.
    SPFUNCTION()
    void SetPosition(double InPos);

    /// Returns where the clip is, in seconds.
    SPFUNCTION()
    double GetPosition() const { return position_; }

    /// Returns the length of the clip to play in seconds (0 without one).
    SPFUNCTION()
    double GetPlayLength() const;

    /// Sets PlayRate (finite).
    SPFUNCTION()
    void SetPlayRate(double Rate);

    /// Returns PlayRate.
    SPFUNCTION()
    double GetPlayRate() const { return PlayRate; }

    /// Sets AnimToPlay (checked as PlayAnimation() checks it) without playing it.
    SPFUNCTION()
    void SetAnimToPlay(const std::string& NewAnimToPlay);

    /// Returns every bone's transform in the current pose as a float64 array (bones, 4, 4) of homogeneous
    /// matrices (column 3 the translation), in Space: the whole pose in one call.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetBoneTransforms(EBoneSpaces Space = EBoneSpaces::WorldSpace) const;

    /// Poses the mesh with Transforms, a float64 array (bones, 4, 4) as GetBoneTransforms() returns, in
    /// Space; the clip stops. Raises InvalidArgumentError, leaving the pose as it was, when the shape is not
    /// (GetNumBones(), 4, 4), a value is not finite, a bottom row is not (0, 0, 0, 1) or a matrix scales an
    /// axis to zero.
    SPFUNCTION()
    void SetBoneTransforms(const sp::reflect::SpArray<double>& Transforms,
                           EBoneSpaces Space = EBoneSpaces::WorldSpace);

    Eigen::AlignedBox3d GetLocalBounds() const override;
    ECollisionPrimitive GetMeshCollisionPrimitive() const override;
    void BeginPlay() override;
    void TickComponent(double deltaSeconds) override;

    // For the renderer: the asset (null without a mesh), each bone's transform in the component's space now,
    // and a number that changes whenever those do.
    const std::shared_ptr<const sp::animation::SkeletalMeshData>& GetAsset() const { return asset_; }
    const std::vector<Eigen::Affine3d>& componentSpaceTransforms() const { return componentSpace_; }
    std::uint64_t poseRevision() const { return poseRevision_; }

  private:
    // The clip `name` names for this mesh (NotFound / InvalidArgument as PlayAnimation() says); null for "".
    const sp::animation::AnimClip* findClip(const std::string& name, const char* function);
    // Poses the mesh with `local` (a full pose of the skeleton).
    void setPose(sp::animation::Pose local);
    // Samples the clip at position_.
    void poseFromClip();
    // The component's world transform as a matrix (scale included).
    Eigen::Affine3d worldMatrix() const;
    int boneOrThrow(const std::string& name, const char* function, const char* what) const;

    std::shared_ptr<const sp::animation::SkeletalMeshData> asset_;
    std::shared_ptr<const std::vector<sp::animation::AnimClip>> otherClips_; // a "<file>#<clip>"'s file's
    const sp::animation::AnimClip* clip_ = nullptr; // AnimToPlay's, in asset_ or otherClips_
    double position_ = 0.0;
    bool playing_ = false;
    std::vector<Eigen::Affine3d> componentSpace_;
    std::uint64_t poseRevision_ = 0;
};

/// An actor that shows one skeletal mesh (a character without a controller: a crowd member, a mannequin).
SPCLASS()
class ASkeletalMeshActor : public AActor {
    SP_GENERATED_BODY()
  public:
    ASkeletalMeshActor() {
        SkeletalMeshComponent = CreateDefaultSubobject<USkeletalMeshComponent>("SkeletalMeshComponent");
    }

    /// The skeletal mesh component (also the root component).
    SPPROPERTY(ReadOnly, NotNull)
    USkeletalMeshComponent* SkeletalMeshComponent = nullptr;
};
