#include "core/procedural/pcg_layout.h"

#include <cmath>

#include <gtest/gtest.h>

namespace sp::procedural::pcg {
namespace {

const Eigen::AlignedBox2d kArea(Eigen::Vector2d(-10, -5), Eigen::Vector2d(10, 5));

TEST(PcgLayoutTest, ScatterKeepsItsSpacingStaysInsideAndRepeatsForASeed) {
    ScatterRules rules;
    rules.spacing = 1.5;
    rules.maxCount = 60;
    rules.minScale = 0.5;
    rules.maxScale = 2.0;
    rules.variants = 3;
    std::mt19937_64 a(4), b(4), c(5);
    const auto first = scatter(kArea, rules, {}, a);
    ASSERT_EQ(first.size(), 60u);
    for (size_t i = 0; i < first.size(); ++i) {
        EXPECT_TRUE(kArea.contains(first[i].location.head<2>()));
        EXPECT_GE(first[i].scale.x(), 0.5);
        EXPECT_LE(first[i].scale.x(), 2.0);
        EXPECT_GE(first[i].variant, 0);
        EXPECT_LT(first[i].variant, 3);
        for (size_t j = 0; j < i; ++j)
            EXPECT_GE((first[i].location - first[j].location).head<2>().norm(), 1.5);
    }
    const auto again = scatter(kArea, rules, {}, b);
    const auto other = scatter(kArea, rules, {}, c);
    ASSERT_EQ(again.size(), first.size());
    for (size_t i = 0; i < first.size(); ++i)
        EXPECT_EQ(again[i].location, first[i].location);
    EXPECT_NE(other[0].location, first[0].location);
}

TEST(PcgLayoutTest, ScatterStopsWhenTheAreaIsFullAndAvoidsExclusions) {
    ScatterRules rules;
    rules.spacing = 3.0;
    rules.maxCount = 1000; // far more than fit
    const Eigen::AlignedBox2d hole(Eigen::Vector2d(-3, -3), Eigen::Vector2d(3, 3));
    std::mt19937_64 rng(1);
    const auto placed = scatter(kArea, rules, {hole}, rng);
    EXPECT_LT(placed.size(), 30u); // 200 m^2 at 3 m spacing holds about 20
    EXPECT_GT(placed.size(), 8u);
    for (const Placement& p : placed)
        EXPECT_FALSE(hole.contains(p.location.head<2>()));
}

TEST(PcgLayoutTest, AlongAPolylineEverySpacingMetresOnBothSides) {
    const Polyline line{{0, 0, 0}, {10, 0, 0}, {10, 10, 0}};
    SplineRules rules;
    rules.spacing = 2.5;
    rules.offset = 1.0;
    rules.bothSides = true;
    std::mt19937_64 rng(0);
    const auto placed = alongPolyline(line, rules, rng);
    ASSERT_EQ(placed.size(), 2u * 9u);                                   // 0, 2.5, ..., 20 m
    EXPECT_TRUE(placed[0].location.isApprox(Eigen::Vector3d(0, 1, 0)));  // left of +x is +y
    EXPECT_TRUE(placed[1].location.isApprox(Eigen::Vector3d(0, -1, 0))); // the mirror
    EXPECT_DOUBLE_EQ(placed[0].yawDegrees, 0.0);
    EXPECT_DOUBLE_EQ(placed[1].yawDegrees, 180.0);
    EXPECT_TRUE(placed[10].location.isApprox(Eigen::Vector3d(9, 2.5, 0))); // 12.5 m: on the second leg
    EXPECT_DOUBLE_EQ(placed[10].yawDegrees, 90.0);
}

TEST(PcgLayoutTest, CityBlocksFillTheGridAndKeepOffRoads) {
    CityRules rules;
    rules.blockSize = 20;
    rules.streetWidth = 10;
    rules.lotsPerSide = 2;
    rules.minHeight = 5;
    rules.maxHeight = 25;
    rules.roadWidth = 10;
    const Eigen::AlignedBox2d area(Eigen::Vector2d(0, 0), Eigen::Vector2d(80, 50)); // 3 x 2 blocks
    std::mt19937_64 rng(2);
    const auto all = cityBlocks(area, rules, {}, rng);
    ASSERT_EQ(all.size(), 3u * 2u * 4u);
    for (const Placement& p : all) {
        EXPECT_DOUBLE_EQ(p.scale.x(), 8.0); // 80 % of a 10 m lot
        EXPECT_GE(p.scale.z(), 5.0);
        EXPECT_LE(p.scale.z(), 25.0);
    }
    // A road through the middle of the first column of blocks (x = 10) clears their western lots... and
    // their eastern ones too (their footprints start 1 m from it, within the 5 m kept free).
    const Polyline road{{10, -5, 0}, {10, 55, 0}};
    std::mt19937_64 again(2);
    const auto kept = cityBlocks(area, rules, {road}, again);
    EXPECT_EQ(kept.size(), all.size() - 2u * 4u);
    for (const Placement& p : kept) {
        const Eigen::AlignedBox2d rect(p.location.head<2>().array() - 4.0,
                                       p.location.head<2>().array() + 4.0);
        EXPECT_GE(distanceToPolyline(rect, road), 5.0);
    }
    // Heights do not depend on the road: the buildings left are the same as before.
    EXPECT_EQ(kept.back().scale, all.back().scale);
}

TEST(PcgLayoutTest, DistanceFromARectangleToAPolyline) {
    const Eigen::AlignedBox2d rect(Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 1));
    EXPECT_DOUBLE_EQ(distanceToPolyline(rect, {{5, -3, 0}, {5, 3, 0}}), 3.0);
    EXPECT_DOUBLE_EQ(distanceToPolyline(rect, {{-1, -1, 0}, {3, 2, 0}}), 0.0);            // crosses it
    EXPECT_DOUBLE_EQ(distanceToPolyline(rect, {{1, 0.5, 0}, {1, 0.6, 0}}), 0.0);          // inside it
    EXPECT_NEAR(distanceToPolyline(rect, {{3, 2, 0}, {4, 3, 0}}), std::sqrt(2.0), 1e-12); // corner to corner
}

} // namespace
} // namespace sp::procedural::pcg
