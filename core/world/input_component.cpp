#include "core/world/input_component.h"

#include "core/world/world.h"

bool UInputComponent::isCurrent() const {
    // The world's frame count only advances after its tick, so during the tick that follows an
    // injection it still equals the count recorded at injection time.
    return GetWorld() && GetWorld()->get_frame_count() == injectedForFrame_;
}

FVector UInputComponent::GetActionValue(const std::string& ActionName) const {
    if (!isCurrent())
        return {};
    auto it = actions_.find(ActionName);
    return it == actions_.end() ? FVector{} : it->second;
}

bool UInputComponent::IsActionTriggered(const std::string& ActionName) const {
    return isCurrent() && actions_.contains(ActionName);
}

void UInputComponent::InjectAction(const std::string& actionName, const FVector& value) {
    if (!isCurrent())
        actions_.clear();
    injectedForFrame_ = GetWorld() ? GetWorld()->get_frame_count() : -1;
    actions_[actionName] = value;
}
