// The extreme-value matrix: every model pushed to the limits users reach, each cell
// checked against an independent limit or reference. test_extremes asserts every cell;
// validity_table prints them as docs/validity.md.
#pragma once

#include <string>
#include <vector>

namespace test {

struct ExtremeCheck {
  std::string area;      ///< e.g. "Poisson ratio", "length scale"
  std::string cell;      ///< the case, e.g. "nu = 0.499, two_term, a/h = 5"
  std::string expected;  ///< what must hold, e.g. "warning", "error", "rel. err < 1e-12"
  std::string outcome;   ///< what happened, e.g. "rel. err 3e-15", "error: ..."
  bool ok = false;
};

/// Runs the whole matrix (a few seconds).
std::vector<ExtremeCheck> run_extreme_matrix();

}  // namespace test
