#include "core/zonegraph/road_surface.h"

#include <gtest/gtest.h>

namespace sp::zonegraph {
namespace {

// The area of a mesh's triangles seen from above (counter-clockwise ones positive).
double area(const SurfaceMesh& mesh) {
    double total = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Eigen::Vector3f &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]],
                              &c = mesh.positions[mesh.indices[t + 2]];
        total += 0.5 * double((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    }
    return total;
}

TEST(RoadSurface, AStraightRoadIsAsphaltBetweenSidewalksWithItsLines) {
    const LaneGraph graph =
        LaneGraph::build({{"Main", {{0, 0, 0}, {90, 0, 0}}}}, RoadProfile::twoWayStreet());
    const RoadSurface surface = buildRoadSurface(graph);
    EXPECT_NEAR(area(surface.road), 7.0 * 90.0, 1e-3); // two 3.5 m lanes, faces up
    EXPECT_NEAR(area(surface.sidewalk), 4.0 * 90.0, 1e-3);
    // Solid lines between the driving lanes and the sidewalks; the centre line dashed, 3 m in every 9 m, its
    // dashes centred on the road: 10 of them.
    EXPECT_NEAR(area(surface.markings), 0.12 * (2.0 * 90.0 + 10.0 * 3.0), 1e-3);
    for (const Eigen::Vector3f& p : surface.road.positions)
        EXPECT_FLOAT_EQ(p.z(), 0.02f);
    for (const Eigen::Vector3f& p : surface.markings.positions) {
        EXPECT_FLOAT_EQ(p.z(), 0.03f);
        EXPECT_TRUE(std::abs(p.y()) < 0.07f || std::abs(std::abs(p.y()) - 3.5f) < 0.07f) << p.transpose();
    }
}

TEST(RoadSurface, AJunctionIsPavedBetweenItsRoads) {
    const LaneGraph graph = LaneGraph::build({{"West", {{-50, 0, 0}, {0, 0, 0}}},
                                              {"East", {{0, 0, 0}, {50, 0, 0}}},
                                              {"South", {{0, -50, 0}, {0, 0, 0}}},
                                              {"North", {{0, 0, 0}, {0, 50, 0}}}},
                                             RoadProfile::twoWayStreet());
    const RoadSurface surface = buildRoadSurface(graph);
    // Four roads' asphalt stopping 8.5 m short of the centre (half the road's width and the corner radius),
    // and the patch between, out to the driving lanes' ends (7 m wide at 8.5 m out) and the corner
    // sidewalks' inner edges: the octagon with corners (+-8.5, +-3.5) and (+-3.5, +-8.5), less the slivers
    // where a corner's sidewalk curves inside the octagon's diagonal side.
    const double out = 5.5 + BuildOptions().cornerRadius;
    const double roads = 4.0 * 7.0 * (50.0 - out);
    const double octagon = 4.0 * out * out - 4.0 * 0.5 * (out - 3.5) * (out - 3.5);
    EXPECT_LT(area(surface.road), roads + octagon);
    EXPECT_GT(area(surface.road), roads + octagon - 4.0 * 8.0);
    // Sidewalks along the roads, and round each of the four corners (the connectors between neighbouring
    // roads' sidewalks: a quarter turn about 4 m round, 2 m wide); none across the junction's middle, where
    // the road is.
    const double along = 4.0 * 4.0 * (50.0 - out);
    EXPECT_GT(area(surface.sidewalk), along + 4.0 * 9.0);
    EXPECT_LT(area(surface.sidewalk), along + 4.0 * 16.0);
    // The road and the sidewalks do not overlap: no road triangle's centroid lies in a sidewalk triangle.
    const auto centroids = [](const SurfaceMesh& mesh) {
        std::vector<Eigen::Vector2f> points;
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            points.push_back(((mesh.positions[mesh.indices[t]] + mesh.positions[mesh.indices[t + 1]] +
                               mesh.positions[mesh.indices[t + 2]]) /
                              3.0f)
                                 .head<2>());
        return points;
    };
    const auto edge = [](const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& p) {
        return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
    };
    for (const Eigen::Vector2f& c : centroids(surface.road))
        for (size_t t = 0; t + 2 < surface.sidewalk.indices.size(); t += 3) {
            const Eigen::Vector2f a = surface.sidewalk.positions[surface.sidewalk.indices[t]].head<2>(),
                                  b = surface.sidewalk.positions[surface.sidewalk.indices[t + 1]].head<2>(),
                                  d = surface.sidewalk.positions[surface.sidewalk.indices[t + 2]].head<2>();
            EXPECT_FALSE(edge(a, b, c) > 1e-4f && edge(b, d, c) > 1e-4f && edge(d, a, c) > 1e-4f)
                << "road at " << c.transpose() << " under a sidewalk";
        }
    for (size_t t = 0; t + 2 < surface.sidewalk.indices.size(); t += 3) {
        const Eigen::Vector3f centroid = (surface.sidewalk.positions[surface.sidewalk.indices[t]] +
                                          surface.sidewalk.positions[surface.sidewalk.indices[t + 1]] +
                                          surface.sidewalk.positions[surface.sidewalk.indices[t + 2]]) /
                                         3.0f;
        EXPECT_FALSE(std::abs(centroid.x()) < 3.0f && std::abs(centroid.y()) < 3.0f) << centroid.transpose();
    }
}

} // namespace
} // namespace sp::zonegraph
