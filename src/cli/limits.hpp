// layerjkr CLI: the limits on counts a user gives (docs/development.md, "Limits"). Each bounds
// memory or threads that a typo could otherwise exhaust; the messages name the limit.
#pragma once

#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr::cli {

/// `curve --points` and `discrete --points`: radii of one call (a curve's CSV is ~150 bytes a
/// point, the bootstrap keeps a few doubles per point and replicate). More: several calls.
inline constexpr int kMaxPoints = 100000;
/// `fit-map --jobs`: worker threads.
inline constexpr int kMaxJobs = 1024;

/// Throws InputError "FLAG = V must be in [lo, hi] (the limit, docs/development.md Limits)".
inline void check_count(const std::string& flag, long long value, long long lo, long long hi) {
  if (value < lo || value > hi)
    throw InputError(flag + " = " + std::to_string(value) + " must be in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]" + (value > hi ? " (the limit; see Limits in docs/development.md)" : ""));
}

}  // namespace layerjkr::cli
