// layerjkr front ends (CLI, Python): the curve and summary answers with their error estimates
// and warnings, computed once so that both print the same numbers.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/jkr.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr::cli {

/// Answers whose estimated model error exceeds this get a warning.
constexpr double kWarnError = 0.05;

/// The radii of an --at list, "a1,a2,...": each finite and > 0, at least one; throws
/// InputError naming the item.
std::vector<double> parse_radii(const std::string& text);

struct CurveTable {
  std::vector<AdhesiveState> states;
  std::vector<double> error_est;  ///< estimated relative model error at each radius
  std::vector<std::string> warnings;
  std::string choice_note;  ///< model auto's choice, empty otherwise
};
/// The scene's adhesive states at `radii` [m] (each finite and > 0).
CurveTable curve_table(const Scene& scene, const std::vector<double>& radii);

struct SummaryReport {
  nlohmann::ordered_json json;  ///< the keys of `layerjkr summary`, warnings included
  std::vector<std::string> warnings;
  std::string choice_note;
};
SummaryReport summary_report(const Scene& scene);

}  // namespace layerjkr::cli
