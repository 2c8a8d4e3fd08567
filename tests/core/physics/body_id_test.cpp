#include "core/physics/body_id.h"

#include <sstream>
#include <unordered_set>

#include <gtest/gtest.h>

namespace sp::physics {
namespace {

std::string str(const BodyId& id) {
    std::ostringstream out;
    out << id;
    return out.str();
}

TEST(BodyIdTest, DefaultIsInvalid) {
    EXPECT_FALSE(BodyId().isSet());
    EXPECT_EQ(BodyId(), BodyId::invalid());
    EXPECT_TRUE((BodyId{0, 0}).isSet());
}

TEST(BodyIdTest, PrintsIndexColonGeneration) {
    EXPECT_EQ(str(BodyId{3, 1}), "3:1");
    EXPECT_EQ(str(BodyId::invalid()), "invalid");
}

TEST(BodyIdTest, HashesAndComparesBothFields) {
    EXPECT_NE((BodyId{1, 0}), (BodyId{1, 1}));
    std::unordered_set<BodyId> ids{{1, 0}, {1, 1}, {0, 1}};
    EXPECT_EQ(ids.size(), 3u);
}

} // namespace
} // namespace sp::physics
