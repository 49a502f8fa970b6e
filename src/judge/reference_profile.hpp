// Internal: the profile a reference model (the exact layer) is built on.
#pragma once

#include "layerjkr/profile.hpp"

namespace layerjkr::detail {

/// `profile`, or for a table of more knots than the reference can afford (its quadratures
/// split at every knot: 10 000 points took minutes), the table resampled at 64 equal steps.
ProfilePtr reference_profile(ProfilePtr profile);

}  // namespace layerjkr::detail
