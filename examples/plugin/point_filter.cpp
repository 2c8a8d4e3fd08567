#include "point_filter.h"

#include <vector>

FPointFilterResult APointFilter::Filter(const SpArray<float>& Points, const FVector& Center, float Radius) {
    Points.checkShape({-1, 3}, "APointFilter.Filter(): array 'Points'");
    const auto& shape = Points.getShape();
    SP_CHECK(Radius >= 0, sp::InvalidArgument, "APointFilter.Filter(): Radius must be >= 0, got ", Radius);
    const auto view = Points.getView();
    std::vector<float> inside;
    std::vector<int64_t> rows;
    const double radius2 = double(Radius) * double(Radius);
    for (int64_t row = 0; row < shape[0]; ++row) {
        const float* p = &view[size_t(row) * 3];
        const double dx = p[0] - Center.X, dy = p[1] - Center.Y, dz = p[2] - Center.Z;
        if (dx * dx + dy * dy + dz * dz <= radius2) {
            inside.insert(inside.end(), p, p + 3);
            rows.push_back(row);
        }
    }
    PointsSeen += shape[0];
    FPointFilterResult result;
    result.Points.setDataSource(std::move(inside), {-1, 3});
    result.Indices.setDataSource(std::move(rows));
    return result;
}
