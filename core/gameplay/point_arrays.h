#pragma once
// Points across the reflection boundary as (N, 3) float64 arrays, the form the query functions of navigation
// and lanes take and return many points in; and the checks that refuse non-finite input naming the function.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/reflect/sp_array.h"
#include "core/world/math.h"

namespace sp::gameplay {

// Throws InvalidArgument "<function>: <name> (x, y, z) must be finite" unless every coordinate is.
void checkFinite(const FVector& v, const char* function, const char* name);
// The rows of an (N, 3) float64 array of finite values; throws InvalidArgument naming the array and the first
// bad value otherwise.
int64_t rowsOf(const reflect::SpArray<double>& points, const char* function, const char* name);
FVector rowOf(const reflect::SpArray<double>& points, int64_t i);
// An (N, 3) float64 array of the points.
reflect::SpArray<double> toArray(const std::vector<Eigen::Vector3d>& points, const char* name);

} // namespace sp::gameplay
