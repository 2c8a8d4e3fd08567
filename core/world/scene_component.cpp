#include "core/world/scene_component.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

#include "core/base/error.h"
#include "core/world/actor.h"
#include "core/world/world.h"

USceneComponent::~USceneComponent() {
    // Children of a destroyed component stay where they are in the world.
    for (USceneComponent* child : std::vector<USceneComponent*>(children_))
        child->DetachFromComponent(true);
    if (parent_)
        std::erase(parent_->children_, this);
}

void USceneComponent::checkMovable(const char* function) const {
    const AActor* owner = GetOwner();
    // Static components are fixed while playing; in the editor world they are being placed.
    const bool inEditor = GetWorld() && GetWorld()->is_editor_world();
    SP_CHECK(Mobility != EComponentMobility::Static || !owner || !owner->HasBegunPlay() || inEditor,
             sp::InvalidState, "USceneComponent.", function, "(): ", GetDebugName(),
             " is static; set its Mobility to Movable before moving it");
}

namespace {

// A transform is checked when it is set, so that a NaN or a zero scale is refused by the call that
// brings it instead of breaking physics and rendering on every later frame. The text naming the bad value
// is made only when a check fails: physics writes every simulated body's transform back each frame.
std::string describe(const FVector& v) {
    return "(" + std::to_string(v.X) + ", " + std::to_string(v.Y) + ", " + std::to_string(v.Z) + ")";
}

template <typename Describe>
void checkFinite(const char* function, const char* what, std::initializer_list<double> values,
                 const Describe& text) {
    for (double value : values)
        SP_CHECK(std::isfinite(value), sp::InvalidArgument, "USceneComponent.", function, "(): ", what,
                 " must be finite, got ", text());
}

void checkScale(const char* function, const FVector& scale) {
    const auto text = [&] { return describe(scale); };
    checkFinite(function, "the scale", {scale.X, scale.Y, scale.Z}, text);
    SP_CHECK(scale.X != 0.0 && scale.Y != 0.0 && scale.Z != 0.0, sp::InvalidArgument, "USceneComponent.",
             function, "(): the scale must have no zero component, got ", text());
}

} // namespace

void USceneComponent::SetRelativeLocation(const FVector& NewLocation) {
    checkFinite("SetRelativeLocation", "the location", {NewLocation.X, NewLocation.Y, NewLocation.Z},
                [&] { return describe(NewLocation); });
    checkMovable("SetRelativeLocation");
    RelativeLocation = NewLocation;
}

void USceneComponent::SetRelativeRotation(const FRotator& NewRotation) {
    checkFinite(
        "SetRelativeRotation", "the rotation", {NewRotation.Pitch, NewRotation.Yaw, NewRotation.Roll}, [&] {
            return "(Pitch " + std::to_string(NewRotation.Pitch) + ", Yaw " +
                   std::to_string(NewRotation.Yaw) + ", Roll " + std::to_string(NewRotation.Roll) + ")";
        });
    checkMovable("SetRelativeRotation");
    RelativeRotation = NewRotation;
}

void USceneComponent::SetRelativeScale3D(const FVector& NewScale3D) {
    checkScale("SetRelativeScale3D", NewScale3D);
    checkMovable("SetRelativeScale3D");
    RelativeScale3D = NewScale3D;
}

void USceneComponent::SetRelativeTransform(const FTransform& NewTransform) {
    const FVector& t = NewTransform.Translation;
    const FQuat& q = NewTransform.Rotation;
    checkFinite("SetRelativeTransform", "the location", {t.X, t.Y, t.Z}, [&] { return describe(t); });
    checkFinite("SetRelativeTransform", "the rotation", {q.X, q.Y, q.Z, q.W},
                [] { return std::string("a quaternion with a NaN or inf"); });
    checkScale("SetRelativeTransform", NewTransform.Scale3D);
    checkMovable("SetRelativeTransform");
    RelativeLocation = NewTransform.Translation;
    RelativeRotation = FRotator::fromQuaternion(NewTransform.Rotation.toEigen());
    RelativeScale3D = NewTransform.Scale3D;
}

FTransform USceneComponent::GetRelativeTransform() const {
    return {RelativeLocation, FQuat::fromEigen(RelativeRotation.toQuaternion()), RelativeScale3D};
}

FTransform USceneComponent::GetComponentTransform() const {
    FTransform transform = GetRelativeTransform();
    if (!parent_)
        return transform;
    return transform.composedWith(AttachSocketName.empty() || !parent_->DoesSocketExist(AttachSocketName)
                                      ? parent_->GetComponentTransform()
                                      : parent_->GetSocketTransform(AttachSocketName));
}

FTransform USceneComponent::GetSocketTransform(const std::string& /*InSocketName*/) const {
    return GetComponentTransform();
}

bool USceneComponent::DoesSocketExist(const std::string& /*InSocketName*/) const {
    return false;
}

FVector USceneComponent::GetComponentLocation() const {
    return GetComponentTransform().Translation;
}

FRotator USceneComponent::GetComponentRotation() const {
    return FRotator::fromQuaternion(GetComponentTransform().Rotation.toEigen());
}

FVector USceneComponent::GetComponentScale() const {
    return GetComponentTransform().Scale3D;
}

void USceneComponent::SetWorldTransform(const FTransform& NewTransform) {
    SetRelativeTransform(parent_ ? NewTransform.relativeTo(parent_->GetComponentTransform()) : NewTransform);
}

void USceneComponent::SetWorldLocation(const FVector& NewLocation) {
    FTransform world = GetComponentTransform();
    world.Translation = NewLocation;
    SetWorldTransform(world);
}

void USceneComponent::SetWorldRotation(const FRotator& NewRotation) {
    FTransform world = GetComponentTransform();
    world.Rotation = FQuat::fromEigen(NewRotation.toQuaternion());
    SetWorldTransform(world);
}

FVector USceneComponent::GetForwardVector() const {
    return FVector::fromEigen(GetComponentTransform().Rotation.toEigen() * Eigen::Vector3d::UnitX());
}

FVector USceneComponent::GetRightVector() const {
    return FVector::fromEigen(GetComponentTransform().Rotation.toEigen() * Eigen::Vector3d::UnitY());
}

FVector USceneComponent::GetUpVector() const {
    return FVector::fromEigen(GetComponentTransform().Rotation.toEigen() * Eigen::Vector3d::UnitZ());
}

void USceneComponent::AttachToComponent(USceneComponent* Parent, bool bKeepWorldTransform,
                                        const std::string& SocketName) {
    SP_CHECK(Parent, sp::InvalidArgument, "USceneComponent.AttachToComponent(): Parent is None");
    SP_CHECK(SocketName.empty() || Parent->DoesSocketExist(SocketName), sp::NotFound,
             "USceneComponent.AttachToComponent(): ", Parent->GetDebugName(), " has no socket '", SocketName,
             "'");
    for (const USceneComponent* p = Parent; p; p = p->parent_)
        SP_CHECK(p != this, sp::InvalidArgument, "USceneComponent.AttachToComponent(): attaching ",
                 GetDebugName(), " to ", Parent->GetDebugName(), " would make a cycle");
    const FTransform world = GetComponentTransform();
    if (parent_)
        std::erase(parent_->children_, this);
    parent_ = Parent;
    Parent->children_.push_back(this);
    AttachSocketName = SocketName;
    if (bKeepWorldTransform) {
        const FTransform relative = world.relativeTo(
            SocketName.empty() ? Parent->GetComponentTransform() : Parent->GetSocketTransform(SocketName));
        RelativeLocation = relative.Translation;
        RelativeRotation = FRotator::fromQuaternion(relative.Rotation.toEigen());
        RelativeScale3D = relative.Scale3D;
    }
}

void USceneComponent::DetachFromComponent(bool bKeepWorldTransform) {
    if (!parent_)
        return;
    const FTransform world = GetComponentTransform();
    std::erase(parent_->children_, this);
    parent_ = nullptr;
    AttachSocketName.clear();
    if (bKeepWorldTransform) {
        RelativeLocation = world.Translation;
        RelativeRotation = FRotator::fromQuaternion(world.Rotation.toEigen());
        RelativeScale3D = world.Scale3D;
    }
}

std::vector<USceneComponent*> USceneComponent::GetChildrenComponents(bool bIncludeAllDescendants) const {
    std::vector<USceneComponent*> result;
    for (USceneComponent* child : children_) {
        result.push_back(child);
        if (bIncludeAllDescendants) {
            auto descendants = child->GetChildrenComponents(true);
            result.insert(result.end(), descendants.begin(), descendants.end());
        }
    }
    return result;
}
