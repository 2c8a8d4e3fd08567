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

#include "core/animation/body_parts.h"
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

/// What poses a skeletal mesh component while it plays (UE's EAnimationMode, its two data-driven modes).
SPENUM()
enum class EAnimationMode : uint8_t {
    /// One clip, AnimToPlay (PlayAnimation).
    AnimationSingleNode = 0,
    /// The blend space BlendSpace at BlendSpaceInput (SetBlendSpaceInput): what a character's walking drives.
    AnimationBlendSpace = 1,
};

/// One clip of a one-dimensional blend space and the input at which it plays alone (UE's FBlendSample).
SPSTRUCT()
struct FBlendSample {
    SP_GENERATED_BODY()

    /// The clip, named as AnimToPlay names one.
    SPPROPERTY()
    std::string Animation;

    /// The input at which this clip plays alone: for locomotion, the speed in m/s its feet move at.
    SPPROPERTY()
    double SampleValue = 0.0;

    friend bool operator==(const FBlendSample&, const FBlendSample&) = default;
};

/// A human-object motion read from an animated file by USkeletalMeshComponent.ReadMotionFile(): one clip of a
/// file holding a skinned character and the rigid objects it handles, sampled at FrameRate. A dict in Python
/// (its arrays are numpy arrays).
SPSTRUCT(TypedDict)
struct FMotionFile {
    SP_GENERATED_BODY()

    /// The clip read.
    SPPROPERTY()
    std::string Animation;
    /// Frames per second; frame f shows the clip at f / FrameRate seconds, the last at its end.
    SPPROPERTY()
    double FrameRate = 0.0;
    /// The character's bones, in its skeleton's order (as GetBoneName() numbers them).
    SPPROPERTY()
    std::vector<std::string> BoneNames;
    /// float64 (frames, bones, 4, 4): each bone in the character's component space
    /// (EBoneSpaces.ComponentSpace), as SetBoneTransforms() takes them.
    SPPROPERTY()
    sp::reflect::SpArray<double> BoneTransforms{"bone_transforms"};
    /// The rigid nodes with a mesh that the clip moves (the objects handled), by node name.
    SPPROPERTY()
    std::vector<std::string> ObjectNames;
    /// float64 (frames, objects, 4, 4): each object's node in the file's space in spear's axes (metres, Z
    /// up), the character's component at the origin.
    SPPROPERTY()
    sp::reflect::SpArray<double> ObjectTransforms{"object_transforms"};
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

    /// Whether object_ids tells the body parts apart: the mesh is drawn as one slot per (material, bone),
    /// each triangle with the bone that weighs most on its corners, each slot with its own object id
    /// (GetBodyPartOfSlot() names the bone of a slot GetObjectIdInfo() returns). Off: one id per material.
    SPPROPERTY(Setter = SetBodyPartIds)
    bool bBodyPartIds = false;

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

    /// What poses the mesh while it plays: one clip, or the blend space.
    SPPROPERTY()
    EAnimationMode AnimationMode = EAnimationMode::AnimationSingleNode;

    /// A one-dimensional blend space (UE's UBlendSpace1D): clips by increasing SampleValue, all of them
    /// cycles (idle, walk, run). At an input between two samples the pose blends their clips by where it
    /// lies, both at the same fraction of their cycles (UE's sync groups: the feet stay in step); the cycle's
    /// rate blends too, and past the last sample it grows with the input (running faster). Set through
    /// SetBlendSpace(), which checks the clips.
    SPPROPERTY(Setter = SetBlendSpace)
    std::vector<FBlendSample> BlendSpace;

    /// The blend space's input now (a speed in m/s for locomotion); SetBlendSpaceInput() sets it.
    SPPROPERTY(ReadOnly)
    double BlendSpaceInput = 0.0;

    /// Sets the skeletal mesh asset. Returns true; raises NotFoundError naming the file when there is none,
    /// InvalidArgumentError when it cannot be read or has no skeleton. The pose becomes the bind pose, and
    /// the clip to play is looked up again in the new mesh's file.
    SPFUNCTION()
    bool SetSkeletalMesh(const std::string& NewMesh);

    /// Sets the material of one slot, growing the list as needed.
    SPFUNCTION()
    void SetMaterial(int ElementIndex, const std::string& Material);

    /// Sets bBodyPartIds.
    SPFUNCTION()
    void SetBodyPartIds(bool bEnable);

    /// Returns the bone whose body part material slot MaterialSlot is drawn for while bBodyPartIds is set (""
    /// while it is not: a slot is then a material). Raises InvalidArgumentError when there is no such slot.
    SPFUNCTION()
    std::string GetBodyPartOfSlot(int MaterialSlot) const;

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

    /// Sets BlendSpace. Raises InvalidArgumentError when the sample values do not increase or are not finite,
    /// NotFoundError naming a clip the mesh does not have (without a mesh yet, the clips are checked when it
    /// is set).
    SPFUNCTION()
    void SetBlendSpace(const std::vector<FBlendSample>& Samples);

    /// Plays the blend space at Input (finite): AnimationMode becomes AnimationBlendSpace and the mesh plays,
    /// looping. Raises InvalidStateError when BlendSpace is empty or the mesh has none of its clips.
    SPFUNCTION()
    void SetBlendSpaceInput(double Input);

    /// Returns the weight of each sample of BlendSpace in the pose now (they sum to 1 while it plays).
    SPFUNCTION()
    std::vector<double> GetBlendSpaceWeights() const;

    /// Sets AnimToPlay (checked as PlayAnimation() checks it) without playing it.
    SPFUNCTION()
    void SetAnimToPlay(const std::string& NewAnimToPlay);

    /// Returns every bone's transform in the current pose as a float64 array (bones, 4, 4) of homogeneous
    /// matrices (column 3 the translation), in Space: the whole pose in one call.
    SPFUNCTION()
    sp::reflect::SpArray<double> GetBoneTransforms(EBoneSpaces Space = EBoneSpaces::WorldSpace) const;

    /// Returns every bone's transform of each of Components (all with the same number of bones) as one
    /// float64 array (components, bones, 4, 4) in Space: a crowd's poses in one call and one array, which
    /// over RPC is one reply (calling GetBoneTransforms per character sends one array each). Raises
    /// InvalidArgumentError naming the first component whose bone count differs, or a None entry.
    SPFUNCTION()
    static sp::reflect::SpArray<double>
    GetBoneTransformsOfComponents(const std::vector<USkeletalMeshComponent*>& Components,
                                  EBoneSpaces Space = EBoneSpaces::WorldSpace);

    /// Reads clip Animation ("": the file's only clip) of the animated file Filename (glTF 2.0; FBX where
    /// assimp reads it) holding a skinned character and the rigid objects it handles, at FrameRate frames per
    /// second from the clip's start to its end: the character's bones and each moved object's node, frame by
    /// frame (spear.motion.import_motion() makes a motion sequence of it). Raises NotFoundError naming the
    /// file, or the clip and those there are; InvalidArgumentError when the file has no skeleton or no clip,
    /// or FrameRate is not positive or asks for more than a million frames.
    SPFUNCTION()
    static FMotionFile ReadMotionFile(const std::string& Filename, const std::string& Animation,
                                      double FrameRate);

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
    // The mesh to draw in the bind pose (the asset's, or split by body part while bBodyPartIds is set) and,
    // per slot of it, the asset's material slot. Null without a mesh.
    const sp::render::MeshData* renderMesh() const;
    std::uint32_t materialOfSlot(std::size_t slot) const;
    const std::vector<Eigen::Affine3d>& componentSpaceTransforms() const { return componentSpace_; }
    std::uint64_t poseRevision() const { return poseRevision_; }
    // Whether BlendSpace's clips were found in the mesh: SetBlendSpaceInput() can play it.
    bool blendSpaceReady() const { return !blendClips_.empty(); }

  private:
    // The clip `name` names for this mesh (NotFound / InvalidArgument as PlayAnimation() says); null for "".
    const sp::animation::AnimClip* findClip(const std::string& name, const char* function);
    // BlendSpace's clips for the mesh (none without a mesh).
    void resolveBlendSpace(const std::vector<FBlendSample>& samples, const char* function);
    // The two samples around BlendSpaceInput, the second's weight, and the cycles a second there.
    struct BlendPoint {
        std::size_t a = 0, b = 0;
        double alpha = 0.0;
        double rate = 0.0;
    };
    BlendPoint blendPoint() const;
    // Poses the mesh with the blend space at phase_.
    void poseFromBlendSpace();
    // Poses the mesh with `local` (a full pose of the skeleton).
    void setPose(sp::animation::Pose local);
    // Samples the clip at position_.
    void poseFromClip();
    // Writes every bone's transform in `Space` at `data` (16 doubles a bone); returns the end of what it
    // wrote.
    double* writeBoneTransforms(EBoneSpaces Space, double* data) const;
    // The component's world transform as a matrix (scale included).
    Eigen::Affine3d worldMatrix() const;
    int boneOrThrow(const std::string& name, const char* function, const char* what) const;

    std::shared_ptr<const sp::animation::SkeletalMeshData> asset_;
    mutable std::shared_ptr<const sp::animation::BodyPartMesh> bodyParts_; // made on first use for asset_
    // The clips of other files that "<file>#<clip>" names brought in (kept while the mesh is).
    std::vector<std::shared_ptr<const std::vector<sp::animation::AnimClip>>> otherClips_;
    const sp::animation::AnimClip* clip_ = nullptr;          // AnimToPlay's, in asset_ or otherClips_
    std::vector<const sp::animation::AnimClip*> blendClips_; // BlendSpace's, resolved
    double phase_ = 0.0;                                     // the blend space's cycle, in [0, 1)
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
