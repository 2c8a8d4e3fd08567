#include "core/pathtrace/emitters.h"

#include <gtest/gtest.h>

using namespace sp::pathtrace;

namespace {

// Two triangles: a unit right triangle (area 0.5) of radiance 1 and one of area 2 of radiance 3, in the
// planes z = 0 and x = 5.
Emitters twoTriangles() {
    Emitters emitters;
    emitters.add(0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Eigen::Vector3f::Ones());
    emitters.add(1, {5, 0, 0}, {5, 2, 0}, {5, 0, 2}, Eigen::Vector3f::Constant(3.0f));
    emitters.add(2, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}, Eigen::Vector3f::Ones()); // no area: left out
    emitters.add(3, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, Eigen::Vector3f::Zero()); // no light: left out
    return emitters;
}

} // namespace

TEST(Emitters, DrawTrianglesByPowerAndPointsUniformly) {
    const Emitters emitters = twoTriangles();
    ASSERT_EQ(emitters.size(), 2u);
    // Powers 0.5 and 6: the second is drawn 12 times as often.
    int second = 0;
    const int draws = 13000;
    Eigen::Vector2d firstCentroid = Eigen::Vector2d::Zero();
    int first = 0;
    for (int i = 0; i < draws; ++i) {
        const float u0 = (float(i) + 0.5f) / float(draws);
        const float u1 = float((i * 7919) % draws) / float(draws),
                    u2 = float((i * 104729) % draws) / float(draws);
        const EmitterSample s = emitters.sample(u0, u1, u2);
        if (s.shape == 1) {
            ++second;
            EXPECT_FLOAT_EQ(s.point.x(), 5.0f);
            EXPECT_NEAR(std::abs(s.normal.x()), 1.0f, 1e-6f);
        } else {
            ASSERT_EQ(s.shape, 0u);
            EXPECT_GE(s.point.x(), 0.0f);
            EXPECT_GE(s.point.y(), 0.0f);
            EXPECT_LE(s.point.x() + s.point.y(), 1.0f + 1e-6f);
            firstCentroid += s.point.head<2>().cast<double>();
            ++first;
        }
    }
    EXPECT_NEAR(double(second) / draws, 12.0 / 13.0, 0.01);
    firstCentroid /= double(first);
    EXPECT_NEAR(firstCentroid.x(), 1.0 / 3.0, 0.03); // uniform over the triangle: its centroid
    EXPECT_NEAR(firstCentroid.y(), 1.0 / 3.0, 0.03);
}

TEST(Emitters, TheAreaDensityIntegratesToOne) {
    const Emitters emitters = twoTriangles();
    const float total = emitters.pdfArea(Eigen::Vector3f::Ones()) * 0.5f +
                        emitters.pdfArea(Eigen::Vector3f::Constant(3.0f)) * 2.0f;
    EXPECT_NEAR(total, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(emitters.sample(0.99f, 0.3f, 0.3f).pdfArea,
                    emitters.pdfArea(Eigen::Vector3f::Constant(3.0f)));
    EXPECT_TRUE(Emitters().empty());
    EXPECT_EQ(Emitters().pdfArea(Eigen::Vector3f::Ones()), 0.0f);
}
