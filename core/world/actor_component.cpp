#include "core/world/actor_component.h"

#include <algorithm>

bool UActorComponent::ComponentHasTag(const std::string& Tag) const {
    return std::find(ComponentTags.begin(), ComponentTags.end(), Tag) != ComponentTags.end();
}
