#include "core/render/light.h"

#include <cmath>

#include "core/base/error.h"

namespace sp::render {

void Light::validate(const char* function) const {
    SP_CHECK(color.allFinite() && (color.array() >= 0.0f).all(), InvalidArgument, function,
             "(): color must be finite and >= 0, got (", color.transpose(), ")");
    SP_CHECK(std::isfinite(intensity) && intensity >= 0.0f, InvalidArgument, function,
             "(): intensity must be finite and >= 0, got ", intensity);
    SP_CHECK(position.allFinite(), InvalidArgument, function, "(): position must be finite");
    SP_CHECK(direction.allFinite() && direction.norm() > 1e-9, InvalidArgument, function,
             "(): direction must be a finite non-zero vector, got (", direction.transpose(), ")");
    SP_CHECK(std::isfinite(range) && range >= 0.0f, InvalidArgument, function, "(): range must be >= 0, got ",
             range);
    if (type == LightType::Spot) {
        SP_CHECK(outerConeDeg > 0.0f && outerConeDeg < 90.0f, InvalidArgument, function,
                 "(): outerConeDeg must be in (0, 90), got ", outerConeDeg);
        SP_CHECK(innerConeDeg >= 0.0f && innerConeDeg <= outerConeDeg, InvalidArgument, function,
                 "(): innerConeDeg must be in [0, outerConeDeg=", outerConeDeg, "], got ", innerConeDeg);
    }
    if (type == LightType::Rect) {
        // Large enough that intensity / area stays finite in float.
        SP_CHECK(std::isfinite(width) && width >= 1e-6f, InvalidArgument, function,
                 "(): width must be finite and >= 1e-6 m, got ", width);
        SP_CHECK(std::isfinite(height) && height >= 1e-6f, InvalidArgument, function,
                 "(): height must be finite and >= 1e-6 m, got ", height);
        const Eigen::Vector3d n = direction.normalized();
        SP_CHECK(right.allFinite() && up.allFinite() && std::abs(right.norm() - 1.0) < 1e-3 &&
                     std::abs(up.norm() - 1.0) < 1e-3 && std::abs(right.dot(up)) < 1e-3 &&
                     std::abs(right.dot(n)) < 1e-3 && std::abs(up.dot(n)) < 1e-3,
                 InvalidArgument, function,
                 "(): right and up must be unit vectors perpendicular to each other and to direction, got (",
                 right.transpose(), ") and (", up.transpose(), ")");
    }
}

} // namespace sp::render
