// FitOptions::bounds after the solve (fit_steps.hpp): a free parameter that ended at an end of its
// range is where the range put it, not the data; it is held there for the others' error bars and
// reported at its bound, with no error bar of its own.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/short_number.hpp"
#include "fit/run/fit_steps.hpp"

namespace layerjkr::detail {

std::vector<BoundHit> at_user_bounds(const ParameterMap& map, const FitOptions& options, const std::vector<double>& x) {
  std::vector<BoundHit> hits;
  for (const ParameterBound& b : options.bounds) {
    if (!map.is_free(b.parameter)) continue;
    const double xj = x[static_cast<std::size_t>(map.index(b.parameter))];
    const auto at = [&](double v, double* end) {
      const double c = map.coordinate(b.parameter, v, x.data());
      if (!std::isfinite(c) || !(std::abs(xj - c) <= 1e-9 * std::max(1.0, std::abs(c)))) return false;
      *end = v;
      return true;
    };
    double end = 0.0;
    if (at(b.lower, &end) || at(b.upper, &end)) hits.push_back({b, end});
  }
  return hits;
}

void report_user_bounds(const std::vector<BoundHit>& hits, FitSummary* out) {
  for (std::size_t k = 0; k < hits.size(); ++k) {
    const BoundHit& h = hits[k];
    const std::string name = to_string(h.bound.parameter);
    const std::string range = "[" + short_number(h.bound.lower) + ", " + short_number(h.bound.upper) + "]";
    for (ParameterEstimate& e : out->parameters) {
      if (e.parameter != h.bound.parameter) continue;
      e.at_bound = true;
      e.standard_error = std::numeric_limits<double>::quiet_NaN();
      e.identifiable = false;
      e.reason = "at the end " + short_number(h.end) + " of its range " + range + " (bounds): the data would put it "
                 "beyond, so the range decides it" + (k == 0 ? "; the others' error bars are from the fit with it held "
                                                               "there" : "");
    }
    out->warnings.push_back(name + " = " + short_number(h.end) + " at the end of its range " + range + " (bounds): the "
                            "data would put it beyond, so the range decides it, not the data; widen the range or check "
                            "the model");
  }
}

}  // namespace layerjkr::detail
