// SplineCurve against analytic curves: cubic Hermite segments, Catmull-Rom tangents, arc length and its
// inverse, closed loops.
#include "core/procedural/spline_curve.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace sp::procedural {
namespace {

TEST(SplineCurveTest, EvenlySpacedPointsOnALineAreTheLineByArcLength) {
    SplineCurve curve;
    for (int i = 0; i < 5; ++i)
        curve.addPoint({2.0 * i, 1.0, 0.5});
    EXPECT_DOUBLE_EQ(curve.length(), 8.0);
    for (double d : {0.0, 0.3, 3.7, 8.0})
        EXPECT_LT((curve.location(curve.keyAtDistance(d)) - Eigen::Vector3d(d, 1.0, 0.5)).norm(), 1e-12) << d;
    EXPECT_DOUBLE_EQ(curve.distanceAtPoint(3), 6.0);
    EXPECT_EQ(curve.location(curve.keyAtDistance(20.0)), Eigen::Vector3d(8.0, 1.0, 0.5)); // clamped
}

TEST(SplineCurveTest, SegmentsAreCubicHermiteWithCatmullRomTangents) {
    SplineCurve curve;
    const Eigen::Vector3d p0(0, 0, 0), p1(1, 2, 0), p2(3, 1, 1), p3(4, 4, 2);
    for (const auto& p : {p0, p1, p2, p3})
        curve.addPoint(p);
    EXPECT_EQ(curve.tangent(0), p1 - p0); // an open end: the chord to its neighbour
    EXPECT_EQ(curve.tangent(1), 0.5 * (p2 - p0));
    EXPECT_EQ(curve.tangent(3), p3 - p2);
    const double t = 0.3;
    const Eigen::Vector3d m1 = 0.5 * (p2 - p0), m2 = 0.5 * (p3 - p1);
    const Eigen::Vector3d expected = (2 * t * t * t - 3 * t * t + 1) * p1 + (t * t * t - 2 * t * t + t) * m1 +
                                     (-2 * t * t * t + 3 * t * t) * p2 + (t * t * t - t * t) * m2;
    EXPECT_LT((curve.location(1.3) - expected).norm(), 1e-12);
    curve.setTangent(2, Eigen::Vector3d(0, 0, 5)); // a tangent of its own
    EXPECT_EQ(curve.tangent(2), Eigen::Vector3d(0, 0, 5));
    curve.setTangent(2, std::nullopt);
    EXPECT_EQ(curve.tangent(2), 0.5 * (p3 - p1));
}

TEST(SplineCurveTest, ArcLengthMatchesFineIntegrationAndInvertsIt) {
    SplineCurve curve;
    curve.addPoint({0, 0, 0});
    curve.addPoint({1, 0, 0});
    curve.setTangent(0, Eigen::Vector3d(1, 2, 0));
    curve.setTangent(1, Eigen::Vector3d(1, -2, 0));
    // The same cubic summed over a million chords.
    double reference = 0.0;
    Eigen::Vector3d previous = curve.location(0.0);
    const int n = 1000000;
    for (int i = 1; i <= n; ++i) {
        const Eigen::Vector3d next = curve.location(double(i) / n);
        reference += (next - previous).norm();
        previous = next;
    }
    EXPECT_NEAR(curve.length(), reference, 1e-9);
    for (double fraction : {0.1, 0.5, 0.77}) {
        const double key = curve.keyAtDistance(fraction * curve.length());
        // The chord sum up to that key is the asked distance.
        double along = 0.0;
        Eigen::Vector3d from = curve.location(0.0);
        const int steps = 200000;
        for (int i = 1; i <= steps; ++i) {
            const Eigen::Vector3d to = curve.location(key * i / steps);
            along += (to - from).norm();
            from = to;
        }
        EXPECT_NEAR(along, fraction * curve.length(), 1e-8) << fraction;
    }
}

TEST(SplineCurveTest, AClosedLoopOfCirclePointsIsCloseToTheCircle) {
    SplineCurve curve;
    const int n = 16;
    const double radius = 3.0;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * std::numbers::pi * i / n;
        curve.addPoint({radius * std::cos(a), radius * std::sin(a), 0.0});
    }
    curve.setClosedLoop(true);
    EXPECT_EQ(curve.segmentCount(), n);
    EXPECT_NEAR(curve.length(), 2 * std::numbers::pi * radius, 2e-3 * radius); // Catmull-Rom stays close
    for (double key = 0.0; key < n; key += 0.37)
        EXPECT_NEAR(curve.location(key).norm(), radius, 5e-3 * radius) << key;
    EXPECT_LT((curve.location(double(n)) - curve.location(0.0)).norm(), 1e-12); // it closes
}

TEST(SplineCurveTest, NonFiniteKeysAndDistancesGoToTheStart) {
    // The component refuses them; the curve itself must never index a segment with one (the RPC fuzzer
    // reached a NaN distance through it once).
    SplineCurve curve;
    curve.addPoint({0, 0, 0});
    curve.addPoint({1, 0, 0});
    EXPECT_EQ(curve.location(std::nan("")), Eigen::Vector3d(0, 0, 0));
    EXPECT_EQ(curve.keyAtDistance(std::nan("")), 0.0);
    EXPECT_EQ(curve.keyAtDistance(INFINITY), 0.0);
    EXPECT_TRUE(curve.derivative(-INFINITY).allFinite());
}

} // namespace
} // namespace sp::procedural
