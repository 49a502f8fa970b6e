// Internal: computed numbers inside sentences (warnings, notices, refusals), where 17 digits of a
// mesh end or an error estimate read as noise. Values a user gave go through format_double.
#pragma once

#include <string>

namespace layerjkr::detail {

/// Four significant digits (%.4g).
std::string short_number(double v);

}  // namespace layerjkr::detail
