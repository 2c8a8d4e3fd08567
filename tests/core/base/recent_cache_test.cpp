#include "core/base/recent_cache.h"

#include <gtest/gtest.h>

namespace sp::base {
namespace {

TEST(RecentCache, KeepsTheMostRecentlyUsedWithinItsBudget) {
    RecentCache<int> cache(100);
    cache.insert("a", std::make_shared<const int>(1), 40);
    cache.insert("b", std::make_shared<const int>(2), 40);
    ASSERT_NE(cache.find("a"), nullptr); // a is now the most recently used
    cache.insert("c", std::make_shared<const int>(3), 40);
    EXPECT_EQ(cache.find("b"), nullptr) << "the least recently used went";
    EXPECT_EQ(*cache.find("a"), 1);
    EXPECT_EQ(*cache.find("c"), 3);
    EXPECT_EQ(cache.bytes(), 80u);
}

TEST(RecentCache, ReplacingAKeyCountsItsBytesOnceAndTheNewestStaysHoweverLarge) {
    RecentCache<int> cache(100);
    const auto held = cache.insert("a", std::make_shared<const int>(1), 30);
    cache.insert("a", std::make_shared<const int>(2), 50);
    EXPECT_EQ(*cache.find("a"), 2);
    EXPECT_EQ(*held, 1) << "a value handed out stays valid";
    EXPECT_EQ(cache.bytes(), 50u);
    cache.insert("huge", std::make_shared<const int>(3), 500);
    EXPECT_EQ(cache.find("a"), nullptr);
    EXPECT_EQ(*cache.find("huge"), 3);
    EXPECT_EQ(cache.bytes(), 500u);
}

} // namespace
} // namespace sp::base
