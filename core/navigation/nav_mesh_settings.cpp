#include "core/navigation/nav_mesh_settings.h"

#include <cmath>

#include "core/base/error.h"

namespace sp::navigation {

namespace {

void checkPositive(std::string_view function, const char* field, double value) {
    SP_CHECK(std::isfinite(value) && value > 0.0, InvalidArgument, function, ": ", field, " = ", value,
             " must be a finite number > 0");
}

void checkNonNegative(std::string_view function, const char* field, double value) {
    SP_CHECK(std::isfinite(value) && value >= 0.0, InvalidArgument, function, ": ", field, " = ", value,
             " must be a finite number >= 0");
}

} // namespace

void validate(const NavMeshSettings& settings, std::string_view function) {
    checkNonNegative(function, "AgentRadius", settings.agentRadius);
    checkPositive(function, "AgentHeight", settings.agentHeight);
    SP_CHECK(std::isfinite(settings.maxSlopeDegrees) && settings.maxSlopeDegrees > 0.0 &&
                 settings.maxSlopeDegrees < 90.0,
             InvalidArgument, function, ": AgentMaxSlope = ", settings.maxSlopeDegrees,
             " must be in (0, 90) degrees");
    checkNonNegative(function, "AgentMaxStepHeight", settings.maxStepHeight);
    checkPositive(function, "CellSize", settings.cellSize);
    checkPositive(function, "CellHeight", settings.cellHeight);
    checkPositive(function, "TileSize", settings.tileSize);
    checkNonNegative(function, "MinRegionArea", settings.minRegionArea);
    SP_CHECK(settings.tileSize >= 8.0 * settings.cellSize, InvalidArgument, function,
             ": TileSize = ", settings.tileSize, " must be at least 8 cells (", 8.0 * settings.cellSize,
             " m at CellSize ", settings.cellSize, ")");
    // Recast counts in cells (ints): bounded here so that no count overflows.
    SP_CHECK(settings.cellSize >= 0.005, InvalidArgument, function, ": CellSize = ", settings.cellSize,
             " must be >= 0.005 m");
    SP_CHECK(settings.cellHeight >= 0.001, InvalidArgument, function, ": CellHeight = ", settings.cellHeight,
             " must be >= 0.001 m");
    SP_CHECK(settings.agentRadius / settings.cellSize <= 1000.0, InvalidArgument, function,
             ": AgentRadius = ", settings.agentRadius, " is more than 1000 cells of CellSize ",
             settings.cellSize);
    SP_CHECK(settings.agentHeight / settings.cellHeight <= 10000.0 &&
                 settings.maxStepHeight / settings.cellHeight <= 10000.0,
             InvalidArgument, function, ": AgentHeight = ", settings.agentHeight,
             " or AgentMaxStepHeight = ", settings.maxStepHeight, " is more than 10000 cells of CellHeight ",
             settings.cellHeight);
    SP_CHECK(settings.minRegionArea / (settings.cellSize * settings.cellSize) <= 1.0e8, InvalidArgument,
             function, ": MinRegionArea = ", settings.minRegionArea, " is more than 1e8 cells");
    SP_CHECK(settings.tileSize / settings.cellSize <= 4096.0, InvalidArgument, function,
             ": TileSize = ", settings.tileSize, " is more than 4096 cells of CellSize ", settings.cellSize);
}

} // namespace sp::navigation
