// Internal: the least-squares straight line y = mean_y + slope (x - mean_x) through the samples
// `idx` of (x, y), with its residual sum of squares and the slope's standard error.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace layerjkr::detail {

struct LineFit {
  double mean_x = 0.0, mean_y = 0.0;
  double sxx = 0.0;    ///< sum of (x - mean_x)^2; the slope is undefined when it is 0
  double slope = 0.0;
  double rss = 0.0;    ///< residual sum of squares
  double slope_stderr = 0.0;  ///< sqrt(rss / (n - 2) / sxx); 0 with two samples
};

inline LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::size_t>& idx) {
  LineFit f;
  const auto n = static_cast<double>(idx.size());
  for (std::size_t i : idx) f.mean_x += x[i], f.mean_y += y[i];
  f.mean_x /= n;
  f.mean_y /= n;
  double sxy = 0.0;
  for (std::size_t i : idx) f.sxx += (x[i] - f.mean_x) * (x[i] - f.mean_x), sxy += (x[i] - f.mean_x) * (y[i] - f.mean_y);
  if (!(f.sxx > 0.0)) return f;
  f.slope = sxy / f.sxx;
  for (std::size_t i : idx) f.rss += std::pow(y[i] - f.mean_y - f.slope * (x[i] - f.mean_x), 2);
  f.slope_stderr = idx.size() > 2 ? std::sqrt(f.rss / (n - 2.0) / f.sxx) : 0.0;
  return f;
}

}  // namespace layerjkr::detail
