#pragma once
// SP_LOG("Input is [", x, "]") writes one line to stderr with a source location, as in the SPEAR paper's
// Fig. 8. Lines from several threads never interleave.

#include <string_view>

#include "core/base/error.h"

namespace sp::base {
void writeLogLine(std::string_view file, int line, std::string_view message);
} // namespace sp::base

#define SP_LOG(...) ::sp::base::writeLogLine(__FILE__, __LINE__, ::sp::detail::concat(__VA_ARGS__))
