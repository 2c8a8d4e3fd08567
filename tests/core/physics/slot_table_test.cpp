#include "core/physics/detail/slot_table.h"

#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "physics_test_util.h"

namespace sp::physics::detail {
namespace {

TEST(SlotTableTest, ReusesFreedSlotsWithANewGeneration) {
    SlotTable<std::unique_ptr<std::string>> table;
    const BodyId a = table.insert(std::make_unique<std::string>("a"));
    const BodyId b = table.insert(std::make_unique<std::string>("b"));
    table.erase(a);
    EXPECT_EQ(table.find(a), nullptr);
    const BodyId c = table.insert(std::make_unique<std::string>("c"));
    EXPECT_EQ(c, (BodyId{0, 1}));
    EXPECT_EQ(**table.find(c), "c");
    EXPECT_EQ(**table.find(b), "b");
    EXPECT_EQ(table.size(), 2u);
    EXPECT_EQ(table.idAt(0), c);
}

TEST(SlotTableTest, GetNamesTheCallerAndWhyTheIdIsBad) {
    SlotTable<int> table;
    const BodyId id = table.insert(1);
    table.erase(id);
    test::expectThrowMessage<StaleObject>([&] { table.get(id, "F()"); }, "F(): body 0:0 was removed");
    test::expectThrowMessage<StaleObject>(
        [&] {
            table.get(BodyId{0, 5}, "F()");
        },
        "F(): body 0:5 does not exist in this world");
    test::expectThrowMessage<StaleObject>(
        [&] {
            table.get(BodyId{9, 0}, "F()");
        },
        "F(): body 9:0 does not exist in this world");
}

TEST(SlotTableTest, ForEachVisitsLiveValuesInSlotOrder) {
    SlotTable<int> table;
    const BodyId a = table.insert(10);
    table.insert(20);
    table.insert(30);
    table.erase(a);
    std::vector<int> seen;
    table.forEach([&](BodyId, int value) { seen.push_back(value); });
    EXPECT_EQ(seen, (std::vector<int>{20, 30}));
}

} // namespace
} // namespace sp::physics::detail
