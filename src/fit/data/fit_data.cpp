// fit() step 1: the samples of a branch, checked for what a fit needs.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "fit/data/contact_steps.hpp"
#include "core/line_fit.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double linear_trend(const FitData& data, const std::vector<std::size_t>& idx) {
  const LineFit line = fit_line(data.delta, data.P, idx);
  if (!(line.sxx > 0.0)) return 0.0;
  const auto [lo, hi] = std::minmax_element(idx.begin(), idx.end(), [&](auto i, auto j) { return data.delta[i] < data.delta[j]; });
  return std::abs(line.slope) * (data.delta[*hi] - data.delta[*lo]);
}

double second_difference_noise(const std::vector<double>& P, const std::vector<std::size_t>& idx) {
  if (idx.size() < 3) return 0.0;
  std::vector<double> d2;
  d2.reserve(idx.size() - 2);
  for (std::size_t k = 2; k < idx.size(); ++k) d2.push_back(P[idx[k]] - 2.0 * P[idx[k - 1]] + P[idx[k - 2]]);
  const double m = median(d2);
  for (auto& v : d2) v = std::abs(v - m);
  return kMadToSigma * median(d2) / std::sqrt(6.0);
}

namespace {

// The fewest samples a baseline and its noise are taken from.
constexpr std::size_t kMinBaselineSamples = 3;

// The baseline samples (the shallowest quarter of the candidates) are an approach's at rest: their spread
// (data.noise, their MAD) is the curve's own noise - at most twice the third-difference noise of
// the samples in acquisition order - and their force has no trend beyond 3 noise sigmas over
// their span of delta: not a rig's curve, in contact throughout.
bool flat_at_rest(const FitData& data, const std::vector<std::size_t>& by_delta, std::size_t quarter,
                  const std::vector<char>& candidate, bool restrict) {
  std::vector<std::size_t> idx, all(data.P.size());
  for (std::size_t k = 0; k < by_delta.size() && idx.size() < quarter; ++k)
    if (!restrict || candidate[by_delta[k]]) idx.push_back(by_delta[k]);
  if (idx.size() < kMinBaselineSamples) return false;
  // An approach's samples before contact: a retract's tail may be a plateau in tension.
  const auto approach = static_cast<std::size_t>(std::count_if(idx.begin(), idx.end(), [&](std::size_t i) { return !data.retract[i]; }));
  if (2 * approach < idx.size()) return false;
  std::iota(all.begin(), all.end(), std::size_t{0});
  if (data.noise > 2.0 * third_difference_noise(data.P, all)) return false;
  return linear_trend(data, idx) <= 3.0 * data.noise;
}

// A short contact at the end of a long approach (a QI curve: 12 of 500 samples rising 90 pN over
// 20 pN of noise) is too short for the deepest twentieth's mean to stand clear of the lowest
// force: the deepest m samples (3 <= m <= m20) whose mean lies above the baseline by more than
// kSignificantSigmas standard errors (noise / sqrt(m)) are a contact region all the same.
bool deepest_above_baseline(const FitData& data, const std::vector<std::size_t>& by_delta, std::size_t m20) {
  if (!(data.noise > 0.0)) return false;
  double sum = 0.0;
  for (std::size_t m = 1; m <= m20 && m <= by_delta.size(); ++m) {
    sum += data.P[by_delta[by_delta.size() - m]] - data.baseline;
    const double n = static_cast<double>(m);
    if (m >= kMinBaselineSamples && sum / n > kSignificantSigmas * data.noise / std::sqrt(n)) return true;
  }
  return false;
}

}  // namespace

// Retract-only data need not hold a baseline: a tension-only unloading curve, or one around the
// pull-off with a necking tail, has no shallow samples at rest, and the spread of the shallowest
// quarter is the tail's shape, not noise. The contact region is then looked for on the
// unloading branch itself: the retract samples before the observed pull-off (the force minimum,
// in acquisition order) are on the stable JKR branch, where dP/d delta > 0 even in tension; they
// must rise from the minimum towards their deepest ones by more than kSignificantSigmas x the
// second-difference noise. If so, that noise becomes the data's noise (the shallowest quarter's
// spread would call every later feature insignificant).
bool unloading_contact_region(FitData& data, double force_span) {
  std::vector<std::size_t> unloading;
  for (std::size_t i = 0; i < data.P.size(); ++i)
    if (data.retract[i]) unloading.push_back(i);
  if (unloading.size() < 3) return false;
  const auto bottom = std::min_element(unloading.begin(), unloading.end(),
                                       [&](auto i, auto j) { return data.P[i] < data.P[j]; });
  std::vector<std::size_t> before(unloading.begin(), bottom + 1);  // up to the pull-off, inclusive
  if (before.size() < 3) return false;
  const double noise = second_difference_noise(data.P, unloading);
  std::vector<std::size_t> by_delta = before;
  std::sort(by_delta.begin(), by_delta.end(), [&](auto i, auto j) { return data.delta[i] > data.delta[j]; });
  const std::size_t m20 = std::max<std::size_t>(1, by_delta.size() / 20);
  double deep = 0.0;
  for (std::size_t k = 0; k < m20; ++k) deep += data.P[by_delta[k]];
  deep /= static_cast<double>(m20);
  if (!(deep - data.P[*bottom] > std::max(kSignificantSigmas * noise, kSignificantForceFraction * force_span)))
    return false;
  data.noise = noise;
  data.unloading_only = true;
  return true;
}

FitData select_fit_data(const CurveData& curve, const FitOptions& options, double* span,
                        double* force_span) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::size_t> idx = curve.select(options.branch);
  const std::vector<bool> retract = curve.retract_mask();
  if (options.retract_window != RetractWindow::all) {
    // In acquisition order: the retract samples from the largest force down to the window's end.
    std::vector<std::size_t> unloading;
    for (std::size_t i : idx)
      if (retract[i]) unloading.push_back(i);
    if (!unloading.empty()) {
      const auto top = std::max_element(unloading.begin(), unloading.end(),
                                         [&](auto i, auto j) { return curve.P[i] < curve.P[j]; });
      const auto bottom = std::min_element(top, unloading.end(), [&](auto i, auto j) { return curve.P[i] < curve.P[j]; });
      auto end = bottom + 1;  // to_pull_off: down to the force minimum, inclusive
      if (options.retract_window == RetractWindow::force_fraction) {
        const double floor = curve.P[*top] - options.window_fraction * (curve.P[*top] - curve.P[*bottom]);
        end = std::find_if(top, bottom + 1, [&](std::size_t i) { return curve.P[i] < floor; });
      }
      std::vector<std::size_t> kept;
      for (std::size_t i : idx)
        if (!retract[i]) kept.push_back(i);
      kept.insert(kept.end(), top, end);
      std::sort(kept.begin(), kept.end());
      idx = kept;
    }
  }
  FitData data;
  for (auto* v : {&data.delta, &data.P, &data.a, &data.sqrt_weight}) v->reserve(idx.size());
  data.retract.reserve(idx.size());
  // Weights are relative: divided by the largest, a uniform scale of them (1e-200 or 1e200)
  // changes nothing, and no product of weights overflows.
  double largest_weight = 0.0;
  for (std::size_t i : idx) largest_weight = std::max(largest_weight, curve.weight.empty() ? 1.0 : curve.weight[i]);
  data.radius_driven = curve.radius_only();
  for (std::size_t i : idx) {
    data.delta.push_back(data.radius_driven ? curve.a[i] : curve.delta[i]);
    data.P.push_back(curve.P[i]);
    data.a.push_back(curve.a.empty() ? kNaN : curve.a[i]);
    data.sqrt_weight.push_back(curve.weight.empty() ? 1.0 : std::sqrt(curve.weight[i] / largest_weight));
    data.retract.push_back(retract[i]);
  }
  if (curve.a.empty()) data.a.clear();
  double a_max = 0.0;  // measured radii are compared in units of the largest one
  for (double v : data.a)
    if (!std::isnan(v)) a_max = std::max(a_max, v);
  data.a_scale = a_max > 0.0 ? a_max : 1.0;
  const std::size_t p_free = options.free.size();
  if (data.residuals() <= p_free)
    throw InputError(curve.source + ": the " + to_string(options.branch) + " branch has " +
                     std::to_string(data.delta.size()) + " samples; fitting " +
                     std::to_string(p_free) + " parameters needs more samples than parameters");
  const auto [dmin, dmax] = std::minmax_element(data.delta.begin(), data.delta.end());
  const auto [pmin, pmax] = std::minmax_element(data.P.begin(), data.P.end());
  *span = *dmax - *dmin;
  *force_span = *pmax - *pmin;
  if (!(*span > 0.0))
    throw InputError(curve.source + (data.radius_driven ? ": a" : ": delta") + " is constant on the chosen branch; nothing to fit");
  if (!(*force_span > 0.0)) throw InputError(curve.source + ": P is constant on the chosen branch; nothing to fit");
  if (data.radius_driven) {  // every sample is in contact: no baseline; the noise from the trend's residue
    std::vector<std::size_t> all(data.P.size());
    std::iota(all.begin(), all.end(), std::size_t{0});
    data.baseline = 0.0;
    data.noise = second_difference_noise(data.P, all);
    return data;
  }

  {
    // The deepest samples must lie clearly above the lowest force: a loading curve rises
    // with delta, and on retract even an all-tensile contact rises from pull-off.
    std::vector<std::size_t> by_delta(data.delta.size());
    std::iota(by_delta.begin(), by_delta.end(), std::size_t{0});
    std::sort(by_delta.begin(), by_delta.end(), [&](auto i, auto j) { return data.delta[i] < data.delta[j]; });
    const std::size_t m20 = std::max<std::size_t>(1, by_delta.size() / 20);
    double deep = 0.0;
    std::vector<double> shallow;
    for (std::size_t k = 0; k < m20; ++k) deep += data.P[by_delta[by_delta.size() - 1 - k]];
    deep /= static_cast<double>(m20);
    // The baseline comes from the shallowest quarter, but never from retract samples up to the
    // observed pull-off (the force minimum, in acquisition order): those are in contact. An
    // unloading curve with a few samples at rest after its pull-off would otherwise take the
    // pull-off force for the baseline. With too few other samples the data hold no sample at
    // rest: only the unloading rule can find their contact region.
    const std::size_t quarter = std::max<std::size_t>(1, by_delta.size() / 4);
    std::vector<char> candidate(data.P.size(), 1);
    std::size_t bottom = data.P.size();
    for (std::size_t i = 0; i < data.P.size(); ++i)
      if (data.retract[i] && (bottom == data.P.size() || data.P[i] < data.P[bottom])) bottom = i;
    std::size_t candidates = data.P.size();
    for (std::size_t i = 0; i <= bottom && i < data.P.size(); ++i)
      if (data.retract[i]) {
        candidate[i] = 0;
        --candidates;
      }
    const bool restrict = candidates >= kMinBaselineSamples;
    for (std::size_t k = 0; k < by_delta.size() && shallow.size() < quarter; ++k)
      if (!restrict || candidate[by_delta[k]]) shallow.push_back(data.P[by_delta[k]]);
    if (options.baseline_window) {
      baseline_of(data.delta, data.P, options.baseline_window, curve.source, &data.baseline, &data.noise);
    } else {
      data.baseline = median(shallow);
      for (auto& v : shallow) v = std::abs(v - data.baseline);
      data.noise = kMadToSigma * median(shallow);
    }
    const bool at_rest = restrict || bottom == data.P.size();
    const bool whole_branch =
        at_rest && (deep - *std::min_element(data.P.begin(), data.P.end()) > kSignificantSigmas * data.noise ||
                    deepest_above_baseline(data, by_delta, m20));
    // P0 not free: an offset of the samples at rest beyond 3 standard errors of their median
    // (1.2533 sigma / sqrt(n)) is the instrument's, not the sample's - removed, as JPK's software
    // and nanite do, so that the fit's zero is the baseline.
    const bool P0_free = std::find(options.free.begin(), options.free.end(), FitParameter::P0) != options.free.end();
    if (whole_branch && !P0_free && options.remove_offset && flat_at_rest(data, by_delta, quarter, candidate, restrict) &&
        std::abs(data.baseline) > 3.0 * 1.2533 * data.noise / std::sqrt(static_cast<double>(std::max<std::size_t>(shallow.size(), 1)))) {
      for (double& p : data.P) p -= data.baseline;
      data.offset = data.baseline;
      data.baseline = 0.0;
    }
    data.spring_constant = options.cantilever_stiffness.value_or(curve.spring_constant);
    data.contact_slope = contact_slope(data);
    if (!whole_branch && !unloading_contact_region(data, *force_span))
      throw InputError(curve.source + ": no contact region - the force does not grow with delta on the " +
                       to_string(options.branch) + " branch, neither over the whole branch nor over the unloading "
                       "samples before the observed pull-off" + no_contact_hint(data));
  }
  return data;
}

double contact_slope(const FitData& data) {
  const double k = data.spring_constant;
  if (!(k > 0.0) || data.P.empty()) return std::numeric_limits<double>::quiet_NaN();
  // Clearly in contact: a fifth of the way up from the baseline to the largest force, and 10
  // noise sigmas above it; the approach where it has such samples, else the retract.
  const double top = *std::max_element(data.P.begin(), data.P.end());
  const double floor = data.baseline + std::max(10.0 * data.noise, 0.2 * (top - data.baseline));
  std::vector<std::size_t> idx;
  for (bool retract : {false, true}) {
    for (std::size_t i = 0; i < data.P.size(); ++i)
      if (data.retract[i] == retract && data.P[i] > floor) idx.push_back(i);
    if (idx.size() >= 5) break;
    idx.clear();
  }
  if (idx.size() < 5) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> z(data.P.size()), d(data.P.size());
  for (std::size_t i : idx) {
    d[i] = data.P[i] / k;
    z[i] = data.delta[i] + d[i];
  }
  const LineFit line = fit_line(z, d, idx);
  return line.sxx > 0.0 ? line.slope : std::numeric_limits<double>::quiet_NaN();
}

std::string no_contact_hint(const FitData& data) {
  if (data.contact_slope >= kRigidContactSlope)
    return ": the tip does not indent measurably - the contact slope d(deflection)/dz is " +
           short_number(data.contact_slope) + " (1 where the sample does not deform): the sample is far stiffer than "
           "the lever (k = " + short_number(data.spring_constant) + " N/m)";
  return " (check the sign conventions: delta grows towards the sample, P is positive when repulsive; and whether a "
         "baseline offset of the force was removed)";
}

void require_usable_loss_scale(const FitOptions& options, double force_span, const std::string& source) {
  if (options.loss == LossType::none) return;
  const double lo = kLossScaleRange[0] * force_span, hi = kLossScaleRange[1] * force_span;
  if (options.loss_scale >= lo && options.loss_scale <= hi) return;
  throw InputError(source + ": the " + to_string(options.loss) + " loss scale " + short_number(options.loss_scale) +
                   " N is outside its usable range [" + short_number(lo) + ", " + short_number(hi) + "] N (" +
                   short_number(kLossScaleRange[0]) + " to " + short_number(kLossScaleRange[1]) +
                   " times the data's force span " + short_number(force_span) + " N): " +
                   (options.loss_scale < lo ? "every residual would be an outlier" : "the loss would be least squares everywhere") +
                   "; give a scale near the noise (or --loss none)");
}

}  // namespace layerjkr::detail
