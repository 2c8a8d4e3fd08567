#include "core/animation/skeletal_mesh_component.h"

#include <algorithm>
#include <cmath>

#include "core/animation/motion_import.h"
#include "core/base/error.h"
#include "core/base/log.h"

namespace {

FTransform toTransform(const Eigen::Affine3d& matrix) {
    const sp::animation::BoneTransform bone =
        sp::animation::BoneTransform::fromMatrix(matrix, "USkeletalMeshComponent");
    FTransform out;
    out.Translation = FVector::fromEigen(bone.translation);
    out.Rotation = FQuat::fromEigen(bone.rotation);
    out.Scale3D = FVector::fromEigen(bone.scale);
    return out;
}

// Writes `m` row after row (numpy's layout of a float64 (..., 4, 4) array); returns the next place to write.
double* writeRowMajor(const Eigen::Matrix4d& m, double* data) {
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 4; ++column)
            *data++ = m(row, column);
    return data;
}

std::string shapeText(const std::vector<int64_t>& shape) {
    std::string out = "(";
    for (std::size_t i = 0; i < shape.size(); ++i)
        out += (i ? ", " : "") + std::to_string(shape[i]);
    return out + (shape.size() == 1 ? ",)" : ")");
}

std::string joined(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& name : names)
        out += (out.empty() ? "'" : ", '") + name + "'";
    return out.empty() ? "none" : out;
}

} // namespace

bool USkeletalMeshComponent::SetSkeletalMesh(const std::string& NewMesh) {
    std::shared_ptr<const sp::animation::SkeletalMeshData> asset;
    if (!NewMesh.empty())
        asset = sp::animation::importSkeletalMesh(NewMesh); // NotFound, InvalidArgument: nothing changed
    asset_ = std::move(asset);
    bodyParts_.reset();
    SkeletalMesh = NewMesh;
    otherClips_.clear();
    clip_ = nullptr;
    blendClips_.clear();
    playing_ = false;
    position_ = 0.0;
    phase_ = 0.0;
    setPose(asset_ ? asset_->skeleton.bindLocal : sp::animation::Pose{});
    // The clips named before are looked up in the new mesh; one it does not have is kept by name (and the
    // mesh posed as bound), as a scene file may set the names before the mesh.
    if (!AnimToPlay.empty() && asset_) {
        try {
            clip_ = findClip(AnimToPlay, "USkeletalMeshComponent.SetSkeletalMesh");
        } catch (const sp::Error&) {
            clip_ = nullptr;
        }
    }
    try {
        resolveBlendSpace(BlendSpace, "USkeletalMeshComponent.SetSkeletalMesh");
    } catch (const sp::Error&) {
        blendClips_.clear();
    }
    return true;
}

void USkeletalMeshComponent::SetMaterial(int ElementIndex, const std::string& Material) {
    sp::world::setMaterialSlot(Materials, ElementIndex, Material, "USkeletalMeshComponent.SetMaterial()");
}

void USkeletalMeshComponent::SetBodyPartIds(bool bEnable) {
    bBodyPartIds = bEnable;
}

const sp::render::MeshData* USkeletalMeshComponent::renderMesh() const {
    if (!asset_)
        return nullptr;
    if (!bBodyPartIds)
        return &asset_->mesh.mesh;
    if (!bodyParts_) // the same for every component of this asset, made once for all of them
        bodyParts_ = sp::animation::sharedBodyParts(asset_);
    return &bodyParts_->mesh;
}

std::uint32_t USkeletalMeshComponent::materialOfSlot(std::size_t slot) const {
    if (!bBodyPartIds || !renderMesh())
        return std::uint32_t(slot);
    return slot < bodyParts_->materialOfSlot.size() ? bodyParts_->materialOfSlot[slot] : 0;
}

std::string USkeletalMeshComponent::GetBodyPartOfSlot(int MaterialSlot) const {
    const sp::render::MeshData* mesh = renderMesh();
    const int slots = mesh ? int(mesh->submeshCount()) : 0;
    SP_CHECK(MaterialSlot >= 0 && MaterialSlot < slots, sp::InvalidArgument,
             "USkeletalMeshComponent.GetBodyPartOfSlot(): MaterialSlot ", MaterialSlot,
             " is out of range [0, ", slots, ")");
    return bBodyPartIds
               ? asset_->skeleton.names[std::size_t(bodyParts_->boneOfSlot[std::size_t(MaterialSlot)])]
               : std::string();
}

int USkeletalMeshComponent::GetNumBones() const {
    return asset_ ? int(asset_->skeleton.size()) : 0;
}

std::string USkeletalMeshComponent::GetBoneName(int BoneIndex) const {
    SP_CHECK(BoneIndex >= 0 && BoneIndex < GetNumBones(), sp::InvalidArgument,
             "USkeletalMeshComponent.GetBoneName(): BoneIndex ", BoneIndex, " is out of range [0, ",
             GetNumBones(), ")");
    return asset_->skeleton.names[std::size_t(BoneIndex)];
}

int USkeletalMeshComponent::GetBoneIndex(const std::string& BoneName) const {
    return asset_ ? asset_->skeleton.find(BoneName) : -1;
}

int USkeletalMeshComponent::boneOrThrow(const std::string& name, const char* function,
                                        const char* what) const {
    const int bone = GetBoneIndex(name);
    SP_CHECK(bone >= 0, sp::NotFound, "USkeletalMeshComponent.", function, "(): ", GetDebugName(), " has no ",
             what, " '", name, "'",
             asset_ ? " (its skeleton's bones: " + joined(asset_->skeleton.names) + ")"
                    : std::string(" (it has no SkeletalMesh)"));
    return bone;
}

Eigen::Affine3d USkeletalMeshComponent::worldMatrix() const {
    const FTransform world = GetComponentTransform();
    Eigen::Affine3d matrix = Eigen::Affine3d::Identity();
    matrix.translation() = world.Translation.toEigen();
    matrix.linear() =
        world.Rotation.toEigen().normalized().toRotationMatrix() * world.Scale3D.toEigen().asDiagonal();
    return matrix;
}

FTransform USkeletalMeshComponent::GetBoneTransform(const std::string& BoneName, EBoneSpaces Space) const {
    const int bone = boneOrThrow(BoneName, "GetBoneTransform", "bone");
    const FTransform component = toTransform(componentSpace_[std::size_t(bone)]);
    return Space == EBoneSpaces::ComponentSpace ? component : component.composedWith(GetComponentTransform());
}

FTransform USkeletalMeshComponent::GetSocketTransform(const std::string& InSocketName) const {
    if (InSocketName.empty())
        return GetComponentTransform();
    boneOrThrow(InSocketName, "GetSocketTransform", "socket");
    return GetBoneTransform(InSocketName, EBoneSpaces::WorldSpace);
}

bool USkeletalMeshComponent::DoesSocketExist(const std::string& InSocketName) const {
    return GetBoneIndex(InSocketName) >= 0;
}

std::vector<std::string> USkeletalMeshComponent::GetAnimationNames() const {
    std::vector<std::string> names;
    if (asset_)
        for (const sp::animation::AnimClip& clip : asset_->clips)
            names.push_back(clip.name);
    return names;
}

const sp::animation::AnimClip* USkeletalMeshComponent::findClip(const std::string& name,
                                                                const char* function) {
    if (name.empty())
        return nullptr;
    SP_CHECK(asset_, sp::InvalidState, function, "(): ", GetDebugName(), " has no SkeletalMesh to animate");
    const std::size_t hash = name.rfind('#');
    if (hash == std::string::npos) {
        const sp::animation::AnimClip* clip = asset_->findClip(name);
        SP_CHECK(clip, sp::NotFound, function, "(): '", SkeletalMesh, "' has no clip '", name,
                 "' (its clips: ", joined(GetAnimationNames()),
                 "; a clip of another file is '<file>#<clip>')");
        return clip;
    }
    const std::string file = name.substr(0, hash), clipName = name.substr(hash + 1);
    auto clips = std::make_shared<const std::vector<sp::animation::AnimClip>>(
        sp::animation::importAnimations(file, asset_->skeleton));
    for (const sp::animation::AnimClip& clip : *clips)
        if (clip.name == clipName) {
            otherClips_.push_back(std::move(clips));
            return &clip;
        }
    std::vector<std::string> names;
    for (const sp::animation::AnimClip& clip : *clips)
        names.push_back(clip.name);
    SP_THROW(sp::NotFound, function, "(): '", file, "' has no clip '", clipName,
             "' (its clips: ", joined(names), ")");
}

void USkeletalMeshComponent::SetAnimToPlay(const std::string& NewAnimToPlay) {
    // Without a mesh yet (a scene file sets the clip before or after the mesh) the name is kept and checked
    // when the mesh is set.
    clip_ = asset_ ? findClip(NewAnimToPlay, "USkeletalMeshComponent.SetAnimToPlay") : nullptr;
    AnimToPlay = NewAnimToPlay;
    position_ = 0.0;
    playing_ = false;
}

void USkeletalMeshComponent::resolveBlendSpace(const std::vector<FBlendSample>& samples,
                                               const char* function) {
    for (std::size_t i = 0; i < samples.size(); ++i) {
        SP_CHECK(std::isfinite(samples[i].SampleValue) &&
                     (i == 0 || samples[i].SampleValue > samples[i - 1].SampleValue),
                 sp::InvalidArgument, function, "(): BlendSpace[", i,
                 "].SampleValue = ", samples[i].SampleValue,
                 " must be finite and greater than the sample before it");
        SP_CHECK(!samples[i].Animation.empty(), sp::InvalidArgument, function, "(): BlendSpace[", i,
                 "].Animation is empty");
    }
    std::vector<const sp::animation::AnimClip*> clips;
    if (asset_)
        for (const FBlendSample& sample : samples)
            clips.push_back(findClip(sample.Animation, function));
    blendClips_ = std::move(clips);
}

void USkeletalMeshComponent::SetBlendSpace(const std::vector<FBlendSample>& Samples) {
    resolveBlendSpace(Samples, "USkeletalMeshComponent.SetBlendSpace");
    BlendSpace = Samples;
    if (AnimationMode == EAnimationMode::AnimationBlendSpace && playing_)
        poseFromBlendSpace();
}

void USkeletalMeshComponent::SetBlendSpaceInput(double Input) {
    SP_CHECK(std::isfinite(Input), sp::InvalidArgument,
             "USkeletalMeshComponent.SetBlendSpaceInput(): Input is ", Input);
    SP_CHECK(!blendClips_.empty(), sp::InvalidState,
             "USkeletalMeshComponent.SetBlendSpaceInput(): ", GetDebugName(),
             BlendSpace.empty() ? " has an empty BlendSpace" : " has no SkeletalMesh to animate");
    BlendSpaceInput = Input;
    if (AnimationMode != EAnimationMode::AnimationBlendSpace || !playing_) {
        AnimationMode = EAnimationMode::AnimationBlendSpace;
        playing_ = true;
    }
    poseFromBlendSpace();
}

USkeletalMeshComponent::BlendPoint USkeletalMeshComponent::blendPoint() const {
    BlendPoint point;
    const std::size_t last = blendClips_.size() - 1;
    const double input = BlendSpaceInput;
    // Cycles a second of sample i's clip as authored.
    auto cycles = [&](std::size_t i) {
        return blendClips_[i]->duration > 0.0 ? 1.0 / blendClips_[i]->duration : 0.0;
    };
    if (input <= BlendSpace.front().SampleValue || last == 0) {
        point.a = point.b = 0;
    } else if (input >= BlendSpace[last].SampleValue) {
        point.a = point.b = last;
    } else {
        while (point.b < last && BlendSpace[point.b].SampleValue < input)
            ++point.b;
        point.a = point.b - 1;
        point.alpha = (input - BlendSpace[point.a].SampleValue) /
                      (BlendSpace[point.b].SampleValue - BlendSpace[point.a].SampleValue);
    }
    point.rate = cycles(point.a) + point.alpha * (cycles(point.b) - cycles(point.a));
    // Past the last sample the cycle quickens with the input, so that feet keep pace with the ground.
    if (point.a == last && last > 0 && BlendSpace[last].SampleValue > 0.0 &&
        input > BlendSpace[last].SampleValue)
        point.rate *= input / BlendSpace[last].SampleValue;
    return point;
}

std::vector<double> USkeletalMeshComponent::GetBlendSpaceWeights() const {
    std::vector<double> weights(BlendSpace.size(), 0.0);
    if (blendClips_.empty() || blendClips_.size() != BlendSpace.size())
        return weights;
    const BlendPoint point = blendPoint();
    weights[point.a] += 1.0 - point.alpha;
    weights[point.b] += point.alpha;
    return weights;
}

void USkeletalMeshComponent::poseFromBlendSpace() {
    if (!asset_ || blendClips_.empty())
        return;
    const BlendPoint point = blendPoint();
    const sp::animation::AnimClip& a = *blendClips_[point.a];
    const sp::animation::AnimClip& b = *blendClips_[point.b];
    sp::animation::Pose pose = a.sample(asset_->skeleton, phase_ * a.duration);
    if (point.alpha > 0.0)
        pose = sp::animation::blend(pose, b.sample(asset_->skeleton, phase_ * b.duration), point.alpha);
    setPose(std::move(pose));
}

void USkeletalMeshComponent::PlayAnimation(const std::string& NewAnimToPlay, bool bLoop) {
    SP_CHECK(!NewAnimToPlay.empty(), sp::InvalidArgument,
             "USkeletalMeshComponent.PlayAnimation(): NewAnimToPlay is empty (Stop() stops a clip)");
    clip_ = findClip(NewAnimToPlay, "USkeletalMeshComponent.PlayAnimation");
    AnimToPlay = NewAnimToPlay;
    AnimationMode = EAnimationMode::AnimationSingleNode;
    bLooping = bLoop;
    position_ = PlayRate < 0.0 ? clip_->duration : 0.0;
    playing_ = true;
    poseFromClip();
}

void USkeletalMeshComponent::Play(bool bLoop) {
    SP_CHECK(clip_, sp::InvalidState, "USkeletalMeshComponent.Play(): ", GetDebugName(),
             " has no clip to play (set AnimToPlay or call PlayAnimation())");
    bLooping = bLoop;
    AnimationMode = EAnimationMode::AnimationSingleNode;
    if (!bLooping && (PlayRate >= 0.0 ? position_ >= clip_->duration : position_ <= 0.0))
        position_ = PlayRate >= 0.0 ? 0.0 : clip_->duration; // it had ended: from the start again
    playing_ = true;
    poseFromClip();
}

void USkeletalMeshComponent::Stop() {
    playing_ = false;
}

void USkeletalMeshComponent::SetPosition(double InPos) {
    SP_CHECK(std::isfinite(InPos), sp::InvalidArgument, "USkeletalMeshComponent.SetPosition(): InPos is ",
             InPos);
    position_ = std::clamp(InPos, 0.0, GetPlayLength());
    poseFromClip();
}

double USkeletalMeshComponent::GetPlayLength() const {
    return clip_ ? clip_->duration : 0.0;
}

void USkeletalMeshComponent::SetPlayRate(double Rate) {
    sp::checkSetting(std::isfinite(Rate), "USkeletalMeshComponent", "PlayRate", "finite", Rate);
    PlayRate = Rate;
}

double* USkeletalMeshComponent::writeBoneTransforms(EBoneSpaces Space, double* data) const {
    // Row-major 4 x 4 matrices, bone after bone: numpy's layout of a (bones, 4, 4) float64 array.
    if (Space == EBoneSpaces::ComponentSpace) {
        for (const Eigen::Affine3d& bone : componentSpace_)
            data = writeRowMajor(bone.matrix(), data);
        return data;
    }
    // World space: each bone's transform after the component's, the three affine rows multiplied out here.
    // As an Eigen Affine3d product and a copy of its 4 x 4 matrix they took ~30 ns a bone, half the work of
    // reading 64 characters' poses (1152 bones).
    const Eigen::Matrix4d world = worldMatrix().matrix();
    for (const Eigen::Affine3d& bone : componentSpace_) {
        const Eigen::Matrix4d& b = bone.matrix(); // bottom row (0, 0, 0, 1)
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 4; ++column)
                *data++ = world(row, 0) * b(0, column) + world(row, 1) * b(1, column) +
                          world(row, 2) * b(2, column) + world(row, 3) * b(3, column);
        *data++ = 0.0;
        *data++ = 0.0;
        *data++ = 0.0;
        *data++ = 1.0;
    }
    return data;
}

sp::reflect::SpArray<double> USkeletalMeshComponent::GetBoneTransforms(EBoneSpaces Space) const {
    sp::reflect::SpArray<double> out("bone_transforms");
    out.resizeForOverwrite({int64_t(componentSpace_.size()), 4, 4}); // every element written next
    writeBoneTransforms(Space, out.data());
    return out;
}

sp::reflect::SpArray<double>
USkeletalMeshComponent::GetBoneTransformsOfComponents(const std::vector<USkeletalMeshComponent*>& Components,
                                                      EBoneSpaces Space) {
    constexpr const char* kFunction = "USkeletalMeshComponent.GetBoneTransformsOfComponents";
    const std::size_t bones =
        Components.empty() || !Components[0] ? 0 : Components[0]->componentSpace_.size();
    for (std::size_t i = 0; i < Components.size(); ++i) {
        SP_CHECK(Components[i], sp::InvalidArgument, kFunction, "(): Components[", i, "] is None");
        SP_CHECK(Components[i]->componentSpace_.size() == bones, sp::InvalidArgument, kFunction,
                 "(): Components[", i, "] (", Components[i]->GetDebugName(), ") has ",
                 Components[i]->componentSpace_.size(), " bones, Components[0] has ", bones);
    }
    sp::reflect::SpArray<double> out("bone_transforms");
    out.resizeForOverwrite({int64_t(Components.size()), int64_t(bones), 4, 4}); // every element written next
    double* data = out.data();
    for (const USkeletalMeshComponent* component : Components)
        data = component->writeBoneTransforms(Space, data);
    return out;
}

void USkeletalMeshComponent::SetBoneTransforms(const sp::reflect::SpArray<double>& Transforms,
                                               EBoneSpaces Space) {
    constexpr const char* kFunction = "USkeletalMeshComponent.SetBoneTransforms";
    const auto& shape = Transforms.getShape();
    const int64_t bones = GetNumBones();
    SP_CHECK(asset_, sp::InvalidState, kFunction, "(): ", GetDebugName(), " has no SkeletalMesh to pose");
    SP_CHECK(shape.size() == 3 && shape[0] == bones && shape[1] == 4 && shape[2] == 4, sp::InvalidArgument,
             kFunction, "(): Transforms must have shape (", bones, ", 4, 4), got ", shapeText(shape));
    const Eigen::Affine3d toComponent =
        Space == EBoneSpaces::WorldSpace ? worldMatrix().inverse() : Eigen::Affine3d::Identity();
    std::vector<Eigen::Affine3d> component(std::size_t(bones), Eigen::Affine3d::Identity());
    const double* data = Transforms.data();
    for (std::size_t bone = 0; bone < std::size_t(bones); ++bone) {
        Eigen::Matrix4d m;
        for (int row = 0; row < 4; ++row)
            for (int column = 0; column < 4; ++column)
                m(row, column) = data[16 * bone + std::size_t(4 * row + column)];
        SP_CHECK(m.allFinite(), sp::InvalidArgument, kFunction, "(): Transforms[", bone, "] ('",
                 asset_->skeleton.names[bone], "') is not finite");
        SP_CHECK(m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-9), sp::InvalidArgument, kFunction,
                 "(): Transforms[", bone, "] ('", asset_->skeleton.names[bone], "') has bottom row (",
                 m(3, 0), ", ", m(3, 1), ", ", m(3, 2), ", ", m(3, 3), "), not (0, 0, 0, 1)");
        component[bone] = toComponent * Eigen::Affine3d(m);
    }
    sp::animation::Pose local =
        asset_->skeleton.localFromComponent(component, kFunction); // zero scales refused
    playing_ = false;
    setPose(std::move(local));
}

void USkeletalMeshComponent::setPose(sp::animation::Pose local) {
    componentSpace_ = asset_ ? asset_->skeleton.componentSpace(local) : std::vector<Eigen::Affine3d>{};
    ++poseRevision_;
}

void USkeletalMeshComponent::poseFromClip() {
    if (asset_ && clip_)
        setPose(clip_->sample(asset_->skeleton, position_));
}

Eigen::AlignedBox3d USkeletalMeshComponent::GetLocalBounds() const {
    return asset_ ? asset_->bindBounds : Eigen::AlignedBox3d{};
}

ECollisionPrimitive USkeletalMeshComponent::GetMeshCollisionPrimitive() const {
    // A posed mesh has no fixed shape to collide as; a character collides as its capsule (ACharacter), and a
    // user may choose a primitive around the bind pose's bounds (CollisionPrimitive).
    return ECollisionPrimitive::NoCollision;
}

void USkeletalMeshComponent::BeginPlay() {
    if (!asset_ && !SkeletalMesh.empty()) { // named but not loaded (a class's default, set as data)
        try {
            SetSkeletalMesh(SkeletalMesh);
        } catch (const sp::Error& error) {
            SP_LOG("USkeletalMeshComponent: ", GetDebugName(), " shows nothing: ", error.what());
        }
    }
    if (AnimationMode == EAnimationMode::AnimationBlendSpace) {
        if (!blendClips_.empty()) {
            playing_ = true;
            poseFromBlendSpace();
        }
        return;
    }
    if (clip_ && !playing_) {
        position_ = PlayRate < 0.0 ? clip_->duration : 0.0;
        playing_ = true;
        poseFromClip();
    }
}

void USkeletalMeshComponent::TickComponent(double deltaSeconds) {
    if (playing_ && AnimationMode == EAnimationMode::AnimationBlendSpace) {
        if (blendClips_.empty())
            return;
        phase_ = std::fmod(phase_ + deltaSeconds * PlayRate * blendPoint().rate, 1.0);
        if (phase_ < 0.0)
            phase_ += 1.0;
        poseFromBlendSpace();
        return;
    }
    if (!playing_ || !clip_)
        return;
    const double length = clip_->duration;
    position_ += deltaSeconds * PlayRate;
    if (length <= 0.0) {
        position_ = 0.0;
    } else if (position_ > length || position_ < 0.0) {
        if (bLooping) {
            position_ = std::fmod(position_, length);
            if (position_ < 0.0)
                position_ += length;
        } else {
            position_ = std::clamp(position_, 0.0, length);
            playing_ = false; // it holds its last pose
        }
    }
    poseFromClip();
}

FMotionFile USkeletalMeshComponent::ReadMotionFile(const std::string& Filename, const std::string& Animation,
                                                   double FrameRate) {
    const sp::animation::ImportedMotion motion = sp::animation::importMotion(Filename, Animation, FrameRate);
    FMotionFile out;
    out.Animation = motion.clip;
    out.FrameRate = motion.fps;
    out.BoneNames = motion.boneNames;
    out.ObjectNames = motion.objectNames;
    const auto fill = [&](sp::reflect::SpArray<double>& array,
                          const std::vector<std::vector<Eigen::Affine3d>>& frames, std::size_t count) {
        array.resize({int64_t(motion.frames), int64_t(count), 4, 4});
        double* data = array.data();
        for (const auto& frame : frames)
            for (const Eigen::Affine3d& transform : frame)
                data = writeRowMajor(transform.matrix(), data);
    };
    fill(out.BoneTransforms, motion.bones, motion.boneNames.size());
    fill(out.ObjectTransforms, motion.objects, motion.objectNames.size());
    return out;
}
