// fit() with a chosen contact point and range: find the point on the approach samples (or fit
// once for method fit), keep the samples the ranges select, shift the data so that the point
// and its baseline are 0 (the values fit_core gives a fixed delta0 and P0, and the start of a
// free one), fit, and shift the answer back.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "fit/data/contact_steps.hpp"
#include "core/short_number.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

bool has(const FitOptions& options, FitParameter q) {
  return std::find(options.free.begin(), options.free.end(), q) != options.free.end();
}

// gof's power law: Hertz's P ~ delta^(1 + 1/d) for a profile f = B r^d; a sphere or a measured
// tip is a paraboloid at small depth.
double hertz_exponent(const Scene& scene) {
  if (const auto form = scene.profile->power_law_form()) return 1.0 + 1.0 / form->d;
  return 1.5;
}

void check_interval(const std::optional<Interval>& r, const char* name, double lo, double hi, const char* valid) {
  if (!r) return;
  const char* fn = "FitOptions";
  if (!(r->first >= lo && r->first <= hi)) throw DomainError(fn, std::string(name) + " (first)", r->first, valid);
  if (!(r->second >= lo && r->second <= hi)) throw DomainError(fn, std::string(name) + " (second)", r->second, valid);
  if (!(r->first < r->second))
    throw DomainError(fn, std::string(name) + " (second, must exceed first = " + std::to_string(r->first) + ")",
                      r->second, valid);
}

// Per sample of the curve: kept by the ranges (retract samples always are).
std::vector<bool> range_mask(const CurveData& curve, const std::vector<bool>& retract, const FitOptions& options,
                             double d_c, double P_c, std::size_t* kept) {
  std::vector<bool> keep(curve.size(), true);
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  if (options.indentation_range) {
    lo = d_c + options.indentation_range->first;
    hi = d_c + options.indentation_range->second;
  }
  double d_start = -std::numeric_limits<double>::infinity(), d_end = std::numeric_limits<double>::infinity();
  if (options.force_range) {
    std::vector<std::size_t> order;
    double top = 0.0;
    for (std::size_t i = 0; i < curve.size(); ++i)
      if (!retract[i]) {
        order.push_back(i);
        top = std::max(top, curve.P[i] - P_c);
      }
    if (!(top > 0.0))
      throw InputError(curve.source + ": force_range needs an approach force above the baseline (" +
                       std::to_string(P_c) + " N); the approach never exceeds it");
    std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) { return curve.delta[i] < curve.delta[j]; });
    bool started = !(options.force_range->first > 0.0);
    for (std::size_t i : order) {
      if (curve.delta[i] < d_c) continue;
      const double f = (curve.P[i] - P_c) / top;
      if (!started && f >= options.force_range->first) {
        started = true;
        d_start = curve.delta[i];
      }
      if (options.force_range->second < 1.0 && f > options.force_range->second) {
        d_end = curve.delta[i];
        break;
      }
    }
    if (!started) d_start = d_end = 0.0;  // nothing reaches the lower fraction: keep none
  }
  *kept = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    if (retract[i]) continue;
    const double d = curve.delta[i];
    keep[i] = d >= lo && d <= hi && d >= d_start && d < d_end;
    *kept += keep[i] ? 1 : 0;
  }
  return keep;
}

std::string interval_text(const std::optional<Interval>& r, const char* unit) {
  if (!r) return "";
  std::ostringstream o;
  o.precision(6);
  o << "[" << r->first << ", " << r->second << "]" << unit;
  return o.str();
}

}  // namespace

void validate_contact_options(const FitOptions& options) {
  const double inf = std::numeric_limits<double>::max();
  check_interval(options.indentation_range, "indentation_range [m]", -inf, inf, "finite, first < second");
  check_interval(options.force_range, "force_range (fractions of the largest approach force)", 0.0, 1.0,
                 "0 <= first < second <= 1");
  check_interval(options.baseline_window, "baseline_window [m]", -inf, inf, "finite, first < second");
}

bool steered_contact(const FitOptions& options) {
  return options.contact_point != ContactPointMethod::fit || options.indentation_range || options.force_range;
}

std::string contact_point_line(const ContactPointReport& r) {
  if (r.method == ContactPointMethod::fit && std::isnan(r.range_reference)) return "";
  std::ostringstream o;
  o.precision(6);
  o << "  contact point (" << to_string(r.method) << ") " << r.value << " m";
  if (std::isfinite(r.standard_error)) o << " +- " << r.standard_error;
  if (std::isfinite(r.baseline)) o << ", baseline " << r.baseline << " N";
  if (!std::isnan(r.range_reference))
    o << "; range kept " << r.samples_in_range << " of " << r.approach_samples << " approach samples";
  o << "\n";
  return o.str();
}

void report_fitted_contact(const CurveData& curve, const FitOptions& options, FitSummary* s) {
  ContactPointReport& r = s->contact_point;
  r.method = ContactPointMethod::fit;
  if (has(options, FitParameter::delta0)) {
    r.value = (*s)[FitParameter::delta0].value;
    r.standard_error = (*s)[FitParameter::delta0].standard_error;
  } else {
    r.value = 0.0;
  }
  const std::vector<bool> retract = curve.retract_mask();
  r.approach_samples = static_cast<std::size_t>(std::count(retract.begin(), retract.end(), false));
  if (options.branch == Branch::retract) r.approach_samples = 0;
  r.samples_in_range = r.approach_samples;
}

FitSummary fit_steered(const CurveData& curve, const Scene& scene, const FitOptions& options, bool hold_gradual_rise) {
  const ContactPointMethod method = options.contact_point;
  const bool ranged = options.indentation_range || options.force_range;
  if (options.branch == Branch::retract)
    throw InputError(curve.source + ": " +
                     (method != ContactPointMethod::fit ? "contact point '" + std::string(to_string(method)) + "'"
                                                        : std::string("an indentation or force range")) +
                     " needs approach samples, and the fit uses the retract branch (use branch approach or all)");
  FitOptions plain = options;
  plain.contact_point = ContactPointMethod::fit;
  plain.indentation_range.reset();
  plain.force_range.reset();
  const std::vector<bool> retract = curve.retract_mask();
  std::vector<double> ad, aP;
  for (std::size_t i = 0; i < curve.size(); ++i)
    if (!retract[i]) {
      ad.push_back(curve.delta[i]);
      aP.push_back(curve.P[i]);
    }
  ContactPointReport report;
  report.method = method;
  report.approach_samples = ad.size();
  double d_c = 0.0, P_c = 0.0;
  if (method == ContactPointMethod::fit) {
    // Fit, select, refit: the range is measured from the first fit's contact point.
    const FitSummary first = fit_core(curve, scene, plain, false, hold_gradual_rise);
    if (has(options, FitParameter::delta0)) d_c = first[FitParameter::delta0].value;
    if (has(options, FitParameter::P0)) P_c = first[FitParameter::P0].value;
  } else {
    if (ad.empty())
      throw InputError(curve.source + ": contact point '" + to_string(method) + "' needs approach samples; the curve has none");
    ContactPoint cp;
    try {
      cp = find_contact_point(ad, aP, method, hertz_exponent(scene), options.baseline_window);
    } catch (const InputError& e) {
      throw InputError(curve.source + ": " + e.what());
    }
    d_c = cp.delta;
    P_c = cp.baseline;
    report.value = d_c;
    report.standard_error = cp.uncertainty;
    report.baseline = P_c;
  }
  CurveData work = curve;
  work.segment.assign(curve.size(), 0);  // the split must not move when samples are dropped
  for (std::size_t i = 0; i < curve.size(); ++i) work.segment[i] = retract[i] ? 1 : 0;
  std::size_t kept = ad.size();
  if (ranged) {
    const std::vector<bool> keep = range_mask(curve, retract, options, d_c, P_c, &kept);
    if (kept == 0)
      throw InputError(curve.source + ": the range " + interval_text(options.indentation_range, " m indentation") +
                       (options.indentation_range && options.force_range ? " and " : "") +
                       interval_text(options.force_range, " of the largest force") + " from the contact point " +
                       std::to_string(d_c) + " m keeps none of the " + std::to_string(ad.size()) + " approach samples");
    CurveData sub = work;
    for (auto* v : {&sub.delta, &sub.P, &sub.a, &sub.weight}) v->clear();
    sub.segment.clear();
    for (std::size_t i = 0; i < curve.size(); ++i) {
      if (!keep[i]) continue;
      sub.delta.push_back(work.delta[i]);
      sub.P.push_back(work.P[i]);
      if (!work.a.empty()) sub.a.push_back(work.a[i]);
      if (!work.weight.empty()) sub.weight.push_back(work.weight[i]);
      sub.segment.push_back(work.segment[i]);
    }
    work = std::move(sub);
    report.range_reference = d_c;
  }
  // The baseline was measured before the ranges selected samples: a window the selection
  // emptied has done its work.
  if (ranged) plain.baseline_window.reset();
  // Shifted to the found point and baseline (for fit: the first fit's delta0 and P0, so the
  // refit starts where the first ended instead of scanning the window for a point of its own).
  for (double& d : work.delta) d -= d_c;
  for (double& p : work.P) p -= P_c;
  if (plain.baseline_window) plain.baseline_window = Interval{plain.baseline_window->first - d_c, plain.baseline_window->second - d_c};
  FitSummary s = fit_core(work, scene, plain, true, hold_gradual_rise);
  for (double& d : s.delta) d += d_c;
  for (double& p : s.P) p += P_c;
  for (double& p : s.P_fit) p += P_c;
  for (ParameterEstimate& e : s.parameters) {
    const double shift = e.parameter == FitParameter::delta0 ? d_c : e.parameter == FitParameter::P0 ? P_c : 0.0;
    e.value += shift;
    e.initial += shift;
  }
  if (method == ContactPointMethod::fit) {
    report.value = has(options, FitParameter::delta0) ? s[FitParameter::delta0].value : 0.0;
    if (has(options, FitParameter::delta0)) report.standard_error = s[FitParameter::delta0].standard_error;
  }
  report.samples_in_range = kept;
  if (method != ContactPointMethod::fit && has(options, FitParameter::delta0) && s.converged) {
    // The method's point measured the ranges and started the fit; the model's contact point is
    // the fitted delta0, which every modulus reported here comes from.
    const ParameterEstimate& d0 = s[FitParameter::delta0];
    const double apart = d0.value - d_c;
    std::string how_far = short_number(std::fabs(apart)) + " m";
    if (std::isfinite(d0.standard_error) && d0.standard_error > 0.0)
      how_far += ", " + short_number(std::fabs(apart) / d0.standard_error) + " standard errors";
    s.notices.push_back("the contact point (" + std::string(to_string(method)) + ") " + short_number(d_c) +
                        " m measured the ranges and started the fit; the model's contact point is the fitted delta0 = " +
                        short_number(d0.value) + " m (" + how_far + " " + (apart >= 0.0 ? "deeper" : "shallower") +
                        "), from which the estimates come");
  }
  s.contact_point = report;
  return s;
}

}  // namespace layerjkr::detail
