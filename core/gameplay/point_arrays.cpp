#include "core/gameplay/point_arrays.h"

#include <cmath>
#include <string>

#include "core/base/error.h"

namespace sp::gameplay {

void checkFinite(const FVector& v, const char* function, const char* name) {
    SP_CHECK(v.isFinite(), InvalidArgument, function, ": ", name, " (", v.X, ", ", v.Y, ", ", v.Z,
             ") must be finite");
}

int64_t rowsOf(const reflect::SpArray<double>& points, const char* function, const char* name) {
    points.checkShape({-1, 3}, std::string(function) + ": array '" + name + "'");
    const double* data = points.data();
    for (int64_t i = 0; i < points.getSize(); ++i)
        SP_CHECK(std::isfinite(data[i]), InvalidArgument, function, ": ", name, "[", i / 3, ", ", i % 3,
                 "] = ", data[i], " is not finite");
    return points.getShape()[0];
}

FVector rowOf(const reflect::SpArray<double>& points, int64_t i) {
    const double* p = points.data() + 3 * i;
    return {p[0], p[1], p[2]};
}

reflect::SpArray<double> toArray(const std::vector<Eigen::Vector3d>& points, const char* name) {
    reflect::SpArray<double> array(name);
    array.resize({int64_t(points.size()), 3});
    double* out = array.data();
    for (const Eigen::Vector3d& p : points) {
        *out++ = p.x();
        *out++ = p.y();
        *out++ = p.z();
    }
    return array;
}

} // namespace sp::gameplay
