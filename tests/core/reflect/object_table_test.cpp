#include <gtest/gtest.h>

#include "core/base/error.h"
#include "core/engine/engine.h"
#include "core/world/actor.h"

using sp::reflect::ObjectTable;

TEST(ObjectTable, HandlesAreGenerationChecked) {
    sp::engine::registerEngineTypes();
    auto* first = new AActor();
    first->InitObject("First", nullptr);
    const auto handle = first->GetHandle();
    EXPECT_EQ(ObjectTable::find(handle), first);
    ObjectTable::rememberName(*first);
    delete first;
    EXPECT_EQ(ObjectTable::find(handle), nullptr);
    // The slot is reused with a new generation: the old handle never resolves to the new object.
    AActor second;
    EXPECT_EQ(second.GetHandle().index, handle.index);
    EXPECT_NE(second.GetHandle().generation, handle.generation);
    EXPECT_EQ(ObjectTable::find(handle), nullptr);
    try {
        ObjectTable::resolve(handle, "AActor.GetName()");
        FAIL();
    } catch (const sp::StaleObject& e) {
        EXPECT_EQ(std::string(e.what()), "AActor.GetName(): AActor 'First' (handle " +
                                             sp::reflect::toString(handle) + ") was destroyed");
    }
    EXPECT_THROW(ObjectTable::resolve({}, "f"), sp::InvalidArgument);
}
