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
}

} // namespace sp::render
