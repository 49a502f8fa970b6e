// The contact-point methods (contact_point.hpp) and the fit around them: find the point,
// shift the data to it, select the ranges, fit (fit_core), and shift the answer back.
#include "layerjkr/contact_point.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "fit/data/contact_steps.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// threshold: the curve has left the baseline once the force stays above this many sigmas
/// (the significance fit() uses for every force feature).
constexpr double kThresholdSigmas = kSignificantSigmas;
/// rov: the window on each side is at most this fraction of the approach samples and at least
/// kRovMinWindow. On synthetic Hertz curves (docs/fitting.md) a 5 % window lets noise peaks in
/// the baseline win at 1 % noise; 10 % keeps the error within 2 peak half-widths up to 3 %.
constexpr double kRovWindowFraction = 0.1;
constexpr std::size_t kRovMinWindow = 5;
constexpr std::size_t kMinSamples = 10;

struct Sorted {
  std::vector<double> d, P;
  double spacing = 0.0;  ///< median sample spacing [m]
};

Sorted sort_by_delta(const std::vector<double>& delta, const std::vector<double>& P) {
  std::vector<std::size_t> order(delta.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return delta[i] < delta[j]; });
  Sorted s;
  for (std::size_t i : order) {
    s.d.push_back(delta[i]);
    s.P.push_back(P[i]);
  }
  std::vector<double> gaps;
  for (std::size_t i = 1; i < s.d.size(); ++i) gaps.push_back(s.d[i] - s.d[i - 1]);
  s.spacing = median(gaps);
  return s;
}

// Noiseless data have sigma = 0: a floor relative to the force span keeps the ratios finite.
double noise_floor(const std::vector<double>& P) {
  const auto [lo, hi] = std::minmax_element(P.begin(), P.end());
  return kSignificantForceFraction * (*hi - *lo);
}

ContactPoint threshold_point(const Sorted& s, double baseline, double noise) {
  const std::size_t n = s.P.size();
  const double level = std::max(kThresholdSigmas * noise, noise_floor(s.P));
  std::size_t exit = n;
  while (exit > 0 && s.P[exit - 1] - baseline > level) --exit;
  if (exit == n || exit == 0)
    throw InputError(std::string("contact point 'threshold': the force ") +
                     (exit == n ? "does not stay above" : "never comes down to") + " the baseline + " +
                     std::to_string(static_cast<int>(kThresholdSigmas)) + " sigma (" +
                     std::to_string(baseline + level) + " N) at the deepest samples; no contact to find");
  std::size_t c = exit - 1;  // <= level; walk back to the last sample at or below the baseline
  while (c > 0 && s.P[c] - baseline > 0.0) --c;
  ContactPoint out;
  if (s.P[c] - baseline > 0.0) {
    out.delta = s.d[c];
  } else {
    const double y0 = s.P[c] - baseline, y1 = s.P[c + 1] - baseline;
    out.delta = s.d[c] + (s.d[c + 1] - s.d[c]) * (-y0) / (y1 - y0);
  }
  out.uncertainty = s.d[exit] - out.delta;
  return out;
}

ContactPoint rov_point(const Sorted& s, double baseline) {
  const std::size_t n = s.P.size();
  // The window scales with the contact region: half the samples above half the largest force
  // (0.37 of the contact samples of a Hertz curve), at most a tenth of the curve. A fixed
  // fraction of a long baseline would span the whole contact region of a real curve.
  const double top = *std::max_element(s.P.begin(), s.P.end()) - baseline;
  const auto upper = static_cast<std::size_t>(
      std::count_if(s.P.begin(), s.P.end(), [&](double p) { return p - baseline > 0.5 * top; }));
  const std::size_t N = std::max(kRovMinWindow, std::min(static_cast<std::size_t>(std::lround(kRovWindowFraction * n)),
                                                          upper / 2));
  if (n < 2 * N + 2)
    throw InputError("contact point 'rov': " + std::to_string(n) + " approach samples; the ratio of variances needs at least " +
                     std::to_string(2 * N + 2));
  // Prefix sums of P - P[0] (shifted for accuracy) give every window's variance in O(1).
  std::vector<double> s1(n + 1, 0.0), s2(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double y = s.P[i] - s.P[0];
    s1[i + 1] = s1[i] + y;
    s2[i + 1] = s2[i] + y * y;
  }
  auto var = [&](std::size_t a, std::size_t b) {  // samples [a, b)
    const double m = static_cast<double>(b - a), mean = (s1[b] - s1[a]) / m;
    return std::max((s2[b] - s2[a]) / m - mean * mean, 0.0);
  };
  const double floor = noise_floor(s.P) * noise_floor(s.P);
  std::vector<double> rov(n, kNaN);
  std::size_t best = N;
  for (std::size_t i = N; i + N < n; ++i) {
    rov[i] = (var(i + 1, i + N + 1) + floor) / (var(i - N, i + 1) + floor);
    if (rov[i] > rov[best]) best = i;
  }
  const double half = 1.0 + 0.5 * (rov[best] - 1.0);
  std::size_t a = best, b = best;
  while (a > N && rov[a - 1] > half) --a;
  while (b + N + 1 < n && rov[b + 1] > half) ++b;
  ContactPoint out;
  out.delta = s.d[best];
  out.uncertainty = 0.5 * (s.d[b] - s.d[a]);
  return out;
}

ContactPoint gof_point(const Sorted& s, double m) {
  const std::size_t n = s.P.size();
  const double d_scale = s.d.back() - s.d.front();
  const double P_ref = s.P[0];
  // chi^2 of P = P0 + k max(d - d_c, 0)^m at candidate c, (P0, k) by linear least squares.
  auto chi2 = [&](std::size_t c, double* P0) {
    double sx = 0.0, sxx = 0.0, sy = 0.0, sxy = 0.0, syy = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double y = s.P[i] - P_ref;
      const double x = i > c ? std::pow((s.d[i] - s.d[c]) / d_scale, m) : 0.0;
      sx += x;
      sxx += x * x;
      sy += y;
      sxy += x * y;
      syy += y * y;
    }
    const double nn = static_cast<double>(n), det = nn * sxx - sx * sx;
    if (!(det > 0.0)) return std::numeric_limits<double>::infinity();
    const double k = (nn * sxy - sx * sy) / det, b = (sy - k * sx) / nn;
    if (P0) *P0 = P_ref + b;
    if (!(k > 0.0)) return std::numeric_limits<double>::infinity();
    return std::max(syy - 2.0 * b * sy - 2.0 * k * sxy + nn * b * b + 2.0 * b * k * sx + k * k * sxx, 0.0);
  };
  // The candidates leave at least 3 samples in contact. A coarse pass, then every sample
  // around the best coarse candidates: chi^2(c) is smooth on the scale of the coarse step
  // except near its minimum.
  const std::size_t last = n - 4;
  const std::size_t step = std::max<std::size_t>(1, n / 128);
  std::vector<double> cost(n, kNaN);
  auto eval = [&](std::size_t c) {
    if (std::isnan(cost[c])) cost[c] = chi2(c, nullptr);
    return cost[c];
  };
  std::size_t best = 0;
  for (std::size_t c = 0; c <= last; c += step)
    if (eval(c) < eval(best)) best = c;
  const std::size_t lo = best > 2 * step ? best - 2 * step : 0, hi = std::min(last, best + 2 * step);
  for (std::size_t c = lo; c <= hi; ++c)
    if (eval(c) < eval(best)) best = c;
  if (!std::isfinite(eval(best)))
    throw InputError("contact point 'gof': no candidate contact point gives a force rising with delta");
  const double s2 = eval(best) / static_cast<double>(n - 3);
  std::size_t a = best, b = best;
  while (a > 0 && eval(a - 1) - eval(best) <= s2) --a;
  while (b < last && eval(b + 1) - eval(best) <= s2) ++b;
  ContactPoint out;
  out.delta = s.d[best];
  out.uncertainty = 0.5 * (s.d[b] - s.d[a]);
  // Between samples: the parabola through chi^2 at the best candidate and its neighbours puts
  // the point at its vertex, and its curvature gives the Delta chi^2 = s^2 half-width
  // sqrt(2 s^2 / chi''), which is finer than the sample spacing when the data are good.
  if (best > 0 && best < last) {
    const double x0 = s.d[best - 1], x1 = s.d[best], x2 = s.d[best + 1];
    const double y0 = eval(best - 1), y1 = eval(best), y2 = eval(best + 1);
    const double d01 = (y1 - y0) / (x1 - x0), d12 = (y2 - y1) / (x2 - x1), curv = 2.0 * (d12 - d01) / (x2 - x0);
    if (curv > 0.0) {
      const double slope = d01 + 0.5 * curv * (x1 - x0);  // of the parabola, at x1
      out.delta = std::clamp(x1 - slope / curv, x0, x2);
      out.uncertainty = std::max(out.uncertainty, std::sqrt(2.0 * s2 / curv));
    }
  }
  chi2(best, &out.baseline);
  return out;
}

}  // namespace

void baseline_of(const std::vector<double>& delta, const std::vector<double>& P,
                 const std::optional<Interval>& window, const std::string& source, double* baseline,
                 double* noise) {
  std::vector<double> base;
  if (window) {
    for (std::size_t i = 0; i < delta.size(); ++i)
      if (delta[i] >= window->first && delta[i] <= window->second) base.push_back(P[i]);
    if (base.size() < 3) {
      std::ostringstream o;
      o.precision(6);
      o << source << ": the baseline window [" << window->first << ", " << window->second << "] m holds "
        << base.size() << " samples (the data's delta runs from "
        << *std::min_element(delta.begin(), delta.end()) << " to " << *std::max_element(delta.begin(), delta.end())
        << " m); it needs at least 3";
      throw InputError(o.str());
    }
  } else {
    std::vector<std::size_t> order(delta.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return delta[i] < delta[j]; });
    for (std::size_t k = 0; k < std::max<std::size_t>(1, order.size() / 4); ++k) base.push_back(P[order[k]]);
  }
  *baseline = median(base);
  for (auto& v : base) v = std::abs(v - *baseline);
  *noise = kMadToSigma * median(base);
}

}  // namespace detail

ContactPoint find_contact_point(const std::vector<double>& delta, const std::vector<double>& P,
                                ContactPointMethod method, double exponent,
                                const std::optional<Interval>& baseline_window) {
  const char* fn = "find_contact_point";
  if (method == ContactPointMethod::fit)
    throw DomainError(fn, "method (fit: delta0 is fitted with the model; call fit())", 0.0, "threshold, rov or gof");
  if (delta.size() != P.size())
    throw DomainError(fn, "P.size() (must equal delta.size())", static_cast<double>(P.size()),
                      std::to_string(delta.size()));
  if (delta.size() < detail::kMinSamples)
    throw InputError(std::string("contact point '") + to_string(method) + "': " + std::to_string(delta.size()) +
                     " approach samples; it needs at least " + std::to_string(detail::kMinSamples));
  for (std::size_t i = 0; i < delta.size(); ++i)
    if (!std::isfinite(delta[i]) || !std::isfinite(P[i]))
      throw DomainError(fn, "sample (delta, P) not finite; index", static_cast<double>(i), "finite values");
  if (!(exponent > 0.0 && std::isfinite(exponent))) throw DomainError(fn, "exponent", exponent, "finite and > 0");
  const detail::Sorted s = detail::sort_by_delta(delta, P);
  double baseline = 0.0, noise = 0.0;
  detail::baseline_of(s.d, s.P, baseline_window, "contact point", &baseline, &noise);
  ContactPoint out;
  switch (method) {
    case ContactPointMethod::threshold: out = detail::threshold_point(s, baseline, noise); break;
    case ContactPointMethod::rov: out = detail::rov_point(s, baseline); break;
    case ContactPointMethod::gof: out = detail::gof_point(s, exponent); break;
    case ContactPointMethod::fit: break;
  }
  out.method = method;
  if (method != ContactPointMethod::gof) out.baseline = baseline;
  out.noise = noise;
  out.uncertainty = std::max(out.uncertainty, 0.5 * s.spacing);
  return out;
}

}  // namespace layerjkr
