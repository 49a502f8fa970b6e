// The extreme-value matrix: every model pushed to the limits users reach, each cell
// checked against an independent limit or reference. test_extremes asserts every cell;
// validity_table prints them as docs/validity.md.
#pragma once

#include <cstddef>
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

/// A group of the matrix: one cell (or a short sequence whose checks compare each cell with
/// the previous one), named and tagged by area without running anything.
struct ExtremeGroup {
  std::string tag;   ///< the area, e.g. "poisson"
  std::string name;  ///< the cell, e.g. "nu = 0.4999, exact layer"
};

/// Every group, in the matrix's order (cheap: nothing is computed).
std::vector<ExtremeGroup> extreme_groups();

/// The cells of group `index` of extreme_groups(), run alone.
std::vector<ExtremeCheck> run_extreme_group(std::size_t index);

/// Runs the whole matrix, every group in order (a few seconds).
std::vector<ExtremeCheck> run_extreme_matrix();

}  // namespace test
