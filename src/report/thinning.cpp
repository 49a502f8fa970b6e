// Thinning a fitted curve for display (map_report.hpp): extremes per bin of consecutive samples,
// as plotting libraries' min/max decimation does, with the included/excluded boundaries kept.
#include <algorithm>
#include <string>

#include "layerjkr/error.hpp"
#include "layerjkr/map_report.hpp"

namespace layerjkr {
namespace {

// Indices of the smallest and largest finite v[i] in [begin, end) (the first of equals);
// `end` for none.
template <class Value>
void extremes(std::size_t begin, std::size_t end, std::vector<std::size_t>& keep, Value v) {
  std::size_t lo = end, hi = end;
  for (std::size_t i = begin; i < end; ++i) {
    const double x = v(i);
    if (!(x == x)) continue;  // NaN
    if (lo == end || x < v(lo)) lo = i;
    if (hi == end || x > v(hi)) hi = i;
  }
  if (lo != end) keep.push_back(lo);
  if (hi != end) keep.push_back(hi);
}

}  // namespace

std::vector<std::size_t> display_samples(const std::vector<double>& P, const std::vector<double>& P_fit,
                                         const std::vector<bool>& excluded, std::size_t max_points) {
  if (max_points < 8) throw DomainError("display_samples", "max_points", static_cast<double>(max_points), ">= 8");
  const std::size_t n = P.size();
  if (P_fit.size() != n || (!excluded.empty() && excluded.size() != n))
    throw InputError("display_samples: P, P_fit and excluded must have equal lengths (got " + std::to_string(n) + ", " +
                     std::to_string(P_fit.size()) + ", " + std::to_string(excluded.size()) + ")");
  std::vector<std::size_t> keep;
  if (n <= max_points) {
    keep.resize(n);
    for (std::size_t i = 0; i < n; ++i) keep[i] = i;
    return keep;
  }
  keep.push_back(0);
  keep.push_back(n - 1);
  const std::size_t bins = (max_points - 2) / 4;
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t begin = b * n / bins, end = (b + 1) * n / bins;
    extremes(begin, end, keep, [&](std::size_t i) { return P[i]; });
    extremes(begin, end, keep, [&](std::size_t i) { return P[i] - P_fit[i]; });
  }
  for (std::size_t i = 1; i < excluded.size(); ++i)
    if (excluded[i] != excluded[i - 1]) {
      keep.push_back(i - 1);
      keep.push_back(i);
    }
  std::sort(keep.begin(), keep.end());
  keep.erase(std::unique(keep.begin(), keep.end()), keep.end());
  return keep;
}

void thin_for_display(FitSummary& s, std::size_t max_points) {
  const std::size_t n = s.delta.size();
  if (s.P.size() != n) throw InputError("thin_for_display: delta and P must have equal lengths");
  // A curve without a fit (it failed) is thinned by its force alone: its residuals are zero.
  const bool fitted = !s.P_fit.empty();
  const std::vector<std::size_t> keep = display_samples(s.P, fitted ? s.P_fit : s.P, s.excluded, max_points);
  if (keep.size() == n) return;
  std::vector<double> delta(keep.size()), P(keep.size()), P_fit(fitted ? keep.size() : 0);
  std::vector<bool> excluded(s.excluded.empty() ? 0 : keep.size());
  for (std::size_t k = 0; k < keep.size(); ++k) {
    delta[k] = s.delta[keep[k]];
    P[k] = s.P[keep[k]];
    if (fitted) P_fit[k] = s.P_fit[keep[k]];
    if (!excluded.empty()) excluded[k] = s.excluded[keep[k]];
  }
  // Moved in, so the capacity of the full vectors is released.
  s.delta = std::move(delta);
  s.P = std::move(P);
  s.P_fit = std::move(P_fit);
  s.excluded = std::move(excluded);
}

}  // namespace layerjkr
