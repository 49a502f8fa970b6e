// Second readings of a fit (contact_steps.hpp): where one fit's answer rests on a choice the
// data may not make - a gradual return read as a tail, a baseline held fixed, a baseline the data
// do not fix - the curve is fitted the other way too, and the report says what the data prefer.
#include <algorithm>
#include <cmath>
#include <string>

#include "fit/data/contact_steps.hpp"
#include "core/short_number.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

// Sum of squared force residuals over every sample, excluded ones too [N^2].
double total_misfit(const FitSummary& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.P.size(); ++i) sum += (s.P[i] - s.P_fit[i]) * (s.P[i] - s.P_fit[i]);
  return sum;
}

// P0 held at 0 (the data's zero, or the offset of the samples at rest removed) is an assumption
// about the baseline: refitted with P0 free, a P0 beyond 5 of its standard errors from the one
// assumed and a modulus or contact point that moves by more than kFixedBaselineSigmas of its error
// bars say the assumption decides the answer (a QI curve's drifting baseline: E 361 +- 76 Pa with
// P0 fixed, 39 kPa with it free). A warning then gives both; nothing is changed.
constexpr double kFixedBaselineSigmas = 3.0;

}  // namespace

FitSummary fit_once(const CurveData& curve, const Scene& scene, const FitOptions& options, bool hold_gradual_rise) {
  FitSummary out = steered_contact(options) ? fit_steered(curve, scene, options, hold_gradual_rise)
                                                    : fit_core(curve, scene, options, false, hold_gradual_rise);
  if (!steered_contact(options)) report_fitted_contact(curve, options, &out);
  return out;
}

// A retract that returns to the baseline without a jump is a tail - or, on a thin layer under
// fixed grips or a stiff lever, the contact's own branch, which can return to zero force
// smoothly: the data alone cannot tell. Both readings are fitted; the branch is kept where its
// residuals are noise and it follows every sample (the tail's too) better. Both fits' samples are
// fixed before each solves, so neither objective moves; the choice and its evidence are a notice.
FitSummary weigh_gradual_rise(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary tail) {
  if (options.exclusion_sigmas == 0.0 || options.retract_control == RetractControl::load) return tail;
  FitSummary held;
  try {
    held = fit_once(data, scene, options, true);
  } catch (const Error&) {
    return tail;
  }
  const double m_tail = total_misfit(tail), m_held = total_misfit(held);
  const auto rms = [&](double m) {
    return short_number(std::sqrt(m / static_cast<double>(std::max<std::size_t>(1, tail.P.size()))));
  };
  const std::string evidence = "(rms over every sample " + rms(m_held) + " N held, against " + rms(m_tail) +
                               " N with the tail excluded)";
  if (held.converged && !held.residual_structure && m_held < m_tail) {
    held.notices.push_back("the retract's gradual return to the baseline is the contact's own branch: held in "
                           "contact, the model follows it as noise " + evidence);
    return held;
  }
  tail.notices.push_back("the retract's gradual return to the baseline is not the contact's branch: held in contact, "
                         "the model does not follow it as noise " + evidence);
  return tail;
}

void check_fixed_baseline(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary* out) {
  // A contact-point method measured the baseline from the samples at rest, and P0 holds it.
  if (data.radius_only() || options.contact_point != ContactPointMethod::fit ||
      std::find(options.free.begin(), options.free.end(), FitParameter::P0) != options.free.end())
    return;
  // First, cheaply: do the samples the model puts off contact sit at P0 = 0? Their mean residual
  // within kSignificantSigmas standard errors says the baseline holds, and no refit is needed.
  double sum = 0.0;
  std::size_t off = 0;
  for (std::size_t i = 0; i < out->P.size(); ++i)
    if (out->P_fit[i] == 0.0 && !(i < out->excluded.size() && out->excluded[i])) {
      sum += out->P[i];
      ++off;
    }
  const bool off_at_zero = off >= 3 && out->noise > 0.0 &&
                           std::abs(sum / static_cast<double>(off)) <=
                               kSignificantSigmas * out->noise / std::sqrt(static_cast<double>(off));
  if (off_at_zero) return;
  FitOptions o = options;
  o.free.push_back(FitParameter::P0);
  FitSummary with_P0;
  try {
    with_P0 = fit_once(data, scene, o, false);
  } catch (const Error&) {
    return;  // the data cannot say more about their baseline
  }
  // Nested fits: freeing P0 can only lower the cost. One that ends higher stopped in another
  // minimum (a tension-only unloading's P0 taking up the adhesion) and says nothing here.
  if (!with_P0.converged || out->P.empty() || with_P0.final_cost > out->final_cost) return;
  // The data must say the baseline is elsewhere - the free P0 beyond kSignificantSigmas of its
  // error from the one assumed (0, or the offset removed) - before the answer's move is blamed on it.
  const ParameterEstimate& P0 = with_P0[FitParameter::P0];
  if (!(std::abs(P0.value - out->baseline_offset) > kSignificantSigmas * P0.standard_error)) return;
  // Noiseless data: error bars of rounding size say nothing about a baseline.
  const auto [lo, hi] = std::minmax_element(out->P.begin(), out->P.end());
  if (!(out->rms_residual > 1e-9 * (*hi - *lo))) return;
  for (const ParameterEstimate& e : out->parameters) {
    if (e.parameter == FitParameter::w) continue;  // w at its bound has no symmetric error bar
    const ParameterEstimate& f = with_P0[e.parameter];
    const double bar = std::max(e.standard_error, f.standard_error);
    if (!(bar > 0.0) || !(std::abs(e.value - f.value) > kFixedBaselineSigmas * bar)) continue;
    out->warnings.push_back("P0 is fixed at 0, and the answer depends on it: with P0 free, " + std::string(to_string(e.parameter)) +
                            " = " + short_number(f.value) + " +- " + short_number(f.standard_error) + " (P0 = " +
                            short_number(P0.value) + " N, " + short_number(std::abs(P0.value - out->baseline_offset) / P0.standard_error) +
                            " standard errors from the baseline assumed) against " +
                            short_number(e.value) + " +- " + short_number(e.standard_error) +
                            " here; the baseline is not what P0 = 0 assumes - free P0 (--free ...,P0)");
    out->identifiable = false;
    out->identifiability_reason = "the answer depends on the fixed baseline P0 = 0 (" + std::string(to_string(e.parameter)) +
                                  " moves by " + short_number(std::abs(e.value - f.value) / bar) +
                                  " error bars with P0 free)";
    return;
  }
}

// Data with no sample at rest (tension-only unloading) do not fix their baseline: a free P0 can
// take up the adhesion the data show - P0 at the pull-off force, w at 0, a shifted Hertz curve -
// with residuals as small as the JKR curve's at the force's zero (a 25 um sphere's tension-only
// unloading: E 22 % low, "identifiable: yes"). Where the fitted P0 lies away from the force's
// zero, the curve is fitted again with P0 held there, from its own data-driven start; if that
// fits as well (deviance below kUpperBoundDeviance) or better, the data cannot tell the two
// apart: a warning gives the other answer and nothing is called identifiable.
void check_baseline_trade(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary* out) {
  const bool free_P0 = std::find(options.free.begin(), options.free.end(), FitParameter::P0) != options.free.end();
  const bool free_w = std::find(options.free.begin(), options.free.end(), FitParameter::w) != options.free.end();
  if (!free_P0 || !free_w || out->pull_off_baseline_measured || !(out->pull_off_force < 0.0)) return;
  const ParameterEstimate& P0 = (*out)[FitParameter::P0];
  if (!(std::abs(P0.value) > kSignificantSigmas * (std::isfinite(P0.standard_error) ? P0.standard_error : 0.0)))
    return;
  FitOptions o = options;
  o.free.erase(std::find(o.free.begin(), o.free.end(), FitParameter::P0));
  o.remove_offset = false;
  FitSummary at_zero;
  try {
    at_zero = fit_once(data, scene, o, false);
  } catch (const Error&) {
    return;
  }
  const std::size_t n = at_zero.points - at_zero.excluded_count;
  if (!(out->final_cost > 0.0) || n <= out->parameters.size()) return;
  const double deviance = 2.0 * (at_zero.final_cost - out->final_cost) * static_cast<double>(n - out->parameters.size()) /
                          (2.0 * out->final_cost);
  if (!(deviance < kUpperBoundDeviance)) return;  // the data prefer the fitted baseline
  std::string other;
  for (const ParameterEstimate& e : at_zero.parameters)
    other += std::string(other.empty() ? "" : ", ") + to_string(e.parameter) + " = " + short_number(e.value);
  const std::string text =
      "with no sample at rest the data do not fix their baseline: P0 = " + short_number(P0.value) + " N fits, and " +
      (deviance < 0.0 ? "P0 = 0 fits better" : "so does P0 = 0") + " with " + other + " (deviance " +
      short_number(deviance) + (deviance < 0.0 ? "; this fit stopped in another minimum" : "") +
      "): P0 trades with w and the modulus";
  out->warnings.push_back(text + "; fix P0 (a baseline removed beforehand) or give samples at rest");
  out->identifiable = false;
  out->identifiability_reason = text;
}

}  // namespace layerjkr::detail
