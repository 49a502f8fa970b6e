// fit(): the model, the parameter map and the summary; the steps are in fit_data.cpp,
// fit_start.cpp, fit_run.cpp (the Ceres solves) and fit_uncertainty.cpp.
#include "layerjkr/fit.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <limits>

#include "contact_steps.hpp"
#include "fit_run.hpp"
#include "fit_steps.hpp"
#include "retract_reading.hpp"
#include "layerjkr/error.hpp"
#include "time_fit.hpp"

namespace layerjkr {
namespace {

using detail::CurveModel;
using detail::CurveParameters;
using detail::ParameterMap;

bool has(const FitOptions& options, FitParameter q) {
  return std::find(options.free.begin(), options.free.end(), q) != options.free.end();
}

// Every free parameter must be one the model family can vary.
void require_supported(const CurveModel& model, const FitOptions& options, const Scene& scene) {
  for (FitParameter q : options.free)
    if (q == FitParameter::sigma0 && !model.supports(q))
      throw InputError(std::string("fit: free parameter sigma0 (the Dugdale stress) needs adhesion 'maugis_dugdale'; "
                                   "the scene's adhesion is '") +
                       to_string(scene.adhesion.model) + "' on model '" + model.model_name() + "'");
  for (FitParameter q : options.free)
    if (q == FitParameter::E_inf || q == FitParameter::tau || q == FitParameter::beta || q == FitParameter::v_star ||
        q == FitParameter::n)
      throw InputError(std::string("fit: free parameter ") + to_string(q) + " belongs to a law in time: " +
                       (q == FitParameter::v_star || q == FitParameter::n ? "crack kinetics (adhesion.kinetics)"
                                                                          : "a relaxing medium (medium.viscoelastic)") +
                       ", which this scene has not");
  for (FitParameter q : options.free)
    if (!model.supports(q)) {
      std::string why = q == FitParameter::R ? "R can vary only for a paraboloid indenter with a closed-form model"
                        : q == FitParameter::E ? "E can vary only for a layer or half-space medium"
                                               : std::string(to_string(q)) + " is not a parameter of this medium; use E";
      throw InputError(std::string("fit: free parameter ") + to_string(q) + " is not available for model '" +
                       model.model_name() + "' (" + why + ")");
    }
  if (has(options, FitParameter::E) && (has(options, FitParameter::K) || has(options, FitParameter::G)))
    throw InputError("fit: E and K/G cannot both be free (K and G follow from E, nu and h)");
}

// The stiffness that lets the retract go, as the evaluator takes it: 0 for load control,
// infinity for fixed grips. `automatic` without a known stiffness follows the data: fixed grips
// where the contact holds past the force minimum (the reading's release), else load control.
double control_stiffness(const FitOptions& options, const CurveData& curve, const detail::RetractReading& reading) {
  const double k = options.cantilever_stiffness.value_or(curve.spring_constant);
  const bool held = reading.release == detail::Release::held_then_jump || reading.release == detail::Release::held_to_end ||
                    reading.release == detail::Release::held_gradual;
  switch (options.retract_control) {
    case RetractControl::load: return 0.0;
    case RetractControl::fixed_grips: return std::numeric_limits<double>::infinity();
    case RetractControl::automatic:
      return k > 0.0 ? k : held ? std::numeric_limits<double>::infinity() : 0.0;
    case RetractControl::cantilever: break;
  }
  if (!(k > 0.0))
    throw InputError(curve.source + ": retract control 'cantilever' needs the cantilever's spring constant, which "
                                    "the curve does not carry; give it (FitOptions::cantilever_stiffness [N/m])");
  return k;
}

// The notice that says which control the retract was fitted under and why.
std::string control_notice(const FitOptions& options, const detail::RetractReading& reading, double k) {
  const bool automatic = options.retract_control == RetractControl::automatic;
  std::string control = std::isinf(k) ? "fixed grips" : k > 0.0 ? "cantilever (k = " + detail::short_number(k) + " N/m" +
                                                                        (options.cantilever_stiffness ? ", given)" : ", the curve's)")
                                                             : "load";
  if (!automatic) return "retract control: " + control + " (as asked); ";
  if (k > 0.0 && std::isfinite(k)) return "retract control: " + control + "; ";
  if (std::isinf(k)) return "retract control: fixed grips, chosen from the data (the contact holds past the force minimum; " +
                            std::string("--control load keeps load control); ");
  return "retract control: load (no spring constant known" +
         std::string(reading.release == detail::Release::gradual ? "" : "; the data show no contact past the force minimum") + "); ";
}

}  // namespace

ParameterMap detail::make_parameter_map(const FitOptions& options, const ResolvedModel& resolved,
                                        detail::SceneParameters fixed, double span, double force_span) {
  if (has(options, FitParameter::K) || has(options, FitParameter::G))
    fixed.layer_foundation = false;  // K, G vary independently of E
  ParameterMap map;
  map.free = options.free;
  map.fixed = fixed;
  map.slot.fill(-1);
  for (std::size_t j = 0; j < options.free.size(); ++j)
    map.slot[static_cast<int>(options.free[j])] = static_cast<int>(j);
  map.L = span;
  map.F = force_span;
  for (FitParameter q : {FitParameter::K, FitParameter::E, FitParameter::R, FitParameter::G, FitParameter::sigma0,
                         FitParameter::E_inf, FitParameter::tau, FitParameter::beta, FitParameter::v_star, FitParameter::n})
    map.ref[static_cast<int>(q)] = map.fixed_value(q);
  const CurveParameters<double>& f = fixed.values;
  map.G_log = resolved.spec.kind == ModelKind::full_foundation && !resolved.automatic;
  map.G_scale = f.G != 0.0 ? std::abs(f.G) : f.K * span * span;
  map.s_scale = std::sqrt(force_span / span) * 0.1;
  return map;
}

const ParameterEstimate& FitSummary::operator[](FitParameter p) const {
  for (const auto& e : parameters)
    if (e.parameter == p) return e;
  throw Error(std::string("FitSummary: parameter ") + to_string(p) + " was not free in this fit");
}

namespace {

// A w this small a fraction of the data-driven start is at its bound, for the rescue below.
constexpr double kWBoundFraction = 1e-12;
constexpr int kRescueStarts = 8;

FitSummary fit_once(const CurveData& curve, const Scene& scene, const FitOptions& options, bool hold_gradual_rise) {
  FitSummary out = detail::steered_contact(options) ? detail::fit_steered(curve, scene, options, hold_gradual_rise)
                                                    : detail::fit_core(curve, scene, options, false, hold_gradual_rise);
  if (!detail::steered_contact(options)) detail::report_fitted_contact(curve, options, &out);
  return out;
}

// Sum of squared force residuals over every sample, excluded ones too [N^2].
double total_misfit(const FitSummary& s) {
  double sum = 0.0;
  for (std::size_t i = 0; i < s.P.size(); ++i) sum += (s.P[i] - s.P_fit[i]) * (s.P[i] - s.P_fit[i]);
  return sum;
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
    return detail::short_number(std::sqrt(m / static_cast<double>(std::max<std::size_t>(1, tail.P.size()))));
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

// P0 held at 0 (the data's zero, or the offset of the samples at rest removed) is an assumption
// about the baseline: refitted with P0 free, a P0 beyond 5 of its standard errors from the one
// assumed and a modulus or contact point that moves by more than kFixedBaselineSigmas of its error
// bars say the assumption decides the answer (a QI curve's drifting baseline: E 361 +- 76 Pa with
// P0 fixed, 39 kPa with it free). A warning then gives both; nothing is changed.
constexpr double kFixedBaselineSigmas = 3.0;

void check_fixed_baseline(const CurveData& data, const Scene& scene, const FitOptions& options, FitSummary* out) {
  // A contact-point method measured the baseline from the samples at rest, and P0 holds it.
  if (data.radius_only() || options.contact_point != ContactPointMethod::fit ||
      std::find(options.free.begin(), options.free.end(), FitParameter::P0) != options.free.end())
    return;
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
  if (!(std::abs(P0.value - out->baseline_offset) > detail::kSignificantSigmas * P0.standard_error)) return;
  // Noiseless data: error bars of rounding size say nothing about a baseline.
  const auto [lo, hi] = std::minmax_element(out->P.begin(), out->P.end());
  if (!(out->rms_residual > 1e-9 * (*hi - *lo))) return;
  for (const ParameterEstimate& e : out->parameters) {
    if (e.parameter == FitParameter::w) continue;  // w at its bound has no symmetric error bar
    const ParameterEstimate& f = with_P0[e.parameter];
    const double bar = std::max(e.standard_error, f.standard_error);
    if (!(bar > 0.0) || !(std::abs(e.value - f.value) > kFixedBaselineSigmas * bar)) continue;
    out->warnings.push_back("P0 is fixed at 0, and the answer depends on it: with P0 free, " + std::string(to_string(e.parameter)) +
                            " = " + detail::short_number(f.value) + " +- " + detail::short_number(f.standard_error) + " (P0 = " +
                            detail::short_number(P0.value) + " N, " + detail::short_number(std::abs(P0.value - out->baseline_offset) / P0.standard_error) +
                            " standard errors from the baseline assumed) against " +
                            detail::short_number(e.value) + " +- " + detail::short_number(e.standard_error) +
                            " here; the baseline is not what P0 = 0 assumes - free P0 (--free ...,P0)");
    out->identifiable = false;
    out->identifiability_reason = "the answer depends on the fixed baseline P0 = 0 (" + std::string(to_string(e.parameter)) +
                                  " moves by " + detail::short_number(std::abs(e.value - f.value) / bar) +
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
  if (!(std::abs(P0.value) > detail::kSignificantSigmas * (std::isfinite(P0.standard_error) ? P0.standard_error : 0.0)))
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
  if (!(deviance < detail::kUpperBoundDeviance)) return;  // the data prefer the fitted baseline
  std::string other;
  for (const ParameterEstimate& e : at_zero.parameters)
    other += std::string(other.empty() ? "" : ", ") + to_string(e.parameter) + " = " + detail::short_number(e.value);
  const std::string text =
      "with no sample at rest the data do not fix their baseline: P0 = " + detail::short_number(P0.value) + " N fits, and " +
      (deviance < 0.0 ? "P0 = 0 fits better" : "so does P0 = 0") + " with " + other + " (deviance " +
      detail::short_number(deviance) + (deviance < 0.0 ? "; this fit stopped in another minimum" : "") +
      "): P0 trades with w and the modulus";
  out->warnings.push_back(text + "; fix P0 (a baseline removed beforehand) or give samples at rest");
  out->identifiable = false;
  out->identifiability_reason = text;
}

}  // namespace

FitSummary fit(const CurveData& curve, const Scene& scene, const FitOptions& options) {
  const auto t_begin = std::chrono::steady_clock::now();
  options.validate();
  curve.validate();
  if (!scene.profile) throw InputError("fit: the scene has no indenter profile");
  if (scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic || scene.adhesion.kinetics) {
    FitSummary out = detail::fit_in_time(curve, scene, options);
    detail::judge_plausibility(&out);
    out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
    return out;
  }
  // An elastic model holds the force while the indenter rests: dwell samples are not its to fit.
  const CurveData data = curve.without_dwell();
  if (data.radius_only() && detail::steered_contact(options))
    throw InputError(data.source + ": (P, a) data have no displacement: no contact point to find and no indentation "
                                   "range to select (use contact_point fit and no ranges)");
  FitSummary out = fit_once(data, scene, options, false);
  if (out.retract_release == detail::to_string(detail::Release::gradual)) out = weigh_gradual_rise(data, scene, options, std::move(out));
  detail::judge_plausibility(&out);
  if (out.converged) check_fixed_baseline(data, scene, options, &out);
  if (out.converged) check_baseline_trade(data, scene, options, &out);
  if (const std::size_t dwell = curve.dwell_count(); dwell > 0)
    out.notices.push_back(std::to_string(dwell) + " dwell samples (segment 2: the indenter at rest) are not fitted: an "
                          "elastic model holds the force constant there; a relaxation law (medium.viscoelastic) fits them");
  out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
  return out;
}

FitSummary detail::fit_core(const CurveData& curve, const Scene& scene, const FitOptions& options,
                            bool contact_given, bool hold_gradual_rise) {

  double span = 0.0, force_span = 0.0;
  FitData data = detail::select_fit_data(curve, options, &span, &force_span);
  detail::require_usable_loss_scale(options, force_span, curve.source);
  FitSummary out;
  detail::weigh_columns(options, force_span, data, &out);
  if (contact_given) {
    data.contact_given = true;
    data.baseline = 0.0;  // the data were shifted to the found baseline
  }
  detail::SceneParameters fixed;
  const ResolvedModel resolved = resolve_model(scene);
  const std::unique_ptr<CurveModel> model = detail::make_curve_model(scene, resolved, options, span, &fixed);
  out.model = model->model_name();
  out.family = model->family();
  require_supported(*model, options, scene);
  ParameterMap map = make_parameter_map(options, resolved, fixed, span, force_span);  // the start refines it
  if (map.is_free(FitParameter::sigma0) && !(fixed.values.sigma0 > 0.0))
    throw InputError("fit: free parameter sigma0 starts from the scene's Dugdale stress, which is 0 here "
                     "(adhesion.z0 with w = 0): give adhesion.sigma0 or a work of adhesion w > 0");
  if (resolved.spec.ode)
    out.warnings.push_back("solver 'ode' verifies the closed forms; the fit evaluates the same "
                           "foundation in closed form");
  out.warnings.insert(out.warnings.end(), fixed.warnings.begin(), fixed.warnings.end());
  out.warnings.insert(out.warnings.end(), resolved.warnings.begin(), resolved.warnings.end());
  out.notices.insert(out.notices.end(), curve.notes.begin(), curve.notes.end());
  out.notices.insert(out.notices.end(), resolved.notices.begin(), resolved.notices.end());

  std::vector<double> x(options.free.size(), 0.0);
  // What the retract shows - baseline, pull-off, contact, release, tail - from the data alone,
  // once: the objective must not move under the fit.
  detail::RetractReading reading = detail::read_retract(data, options, force_span, hold_gradual_rise);
  const std::vector<double> given_weights = data.sqrt_weight;
  detail::apply_reading(reading, options, data);
  const double k = control_stiffness(options, curve, reading);
  data.cantilever = k > 0.0;
  if (reading.release != detail::Release::none)
    out.notices.push_back(control_notice(options, reading, k) + reading.rule);
  CurveEvaluator ev(*model, map, data, k);
  if (data.radius_driven) {
    if (map.is_free(FitParameter::delta0))
      throw InputError(curve.source + ": (P, a) data have no displacement, so no contact point delta0 to fit; free "
                                      "the stiffness, w and P0 only");
    detail::find_radius_start(data, map, ev, x);
  } else {
    // A model solved per parameter vector has the same medium under JKR scanned instead.
    const CurveModel* start_model = model->start_model();
    if (start_model) {
      CurveEvaluator start_ev(*start_model, map, data, k);
      detail::find_start(data, map, start_ev, x, curve.source);
    } else {
      detail::find_start(data, map, ev, x, curve.source);
    }
  }
  for (FitParameter q : options.free) {
    ParameterEstimate e;
    e.parameter = q;
    e.initial = map.value(q, x.data());
    out.parameters.push_back(e);
  }
  // A start outside the model's domain is a data problem.
  if (!ev.evaluate(x.data(), false))
    throw InputError(curve.source + ": the model cannot be evaluated at the data-driven start "
                                    "(the indentation exceeds the model's range of radii)");

  detail::FitRun run(ev, map, options, data, x);
  // A model built per parameter vector meets its accuracy target at the start and again at the
  // solution, solving once more if it had to refine there.
  const auto physical_at_x = [&] {
    detail::CurveParameters<double> p;
    double d0 = 0.0, P0 = 0.0;
    map.physical(x.data(), &p, &d0, &P0);
    return p;
  };
  const auto refine = [&] {
    if (!model->refine_at(physical_at_x())) return false;
    ev.invalidate();
    return true;
  };
  refine();
  run.solve();
  if (refine()) run.solve();
  run.try_extra_starts();
  // w at its bound while the data's retract goes clearly below the baseline: the solve slid off
  // the adhesion the data show - try again from more starts with w from the dip.
  if (map.is_free(FitParameter::w) && data.adhesive &&
      map.value(FitParameter::w, x.data()) <= kWBoundFraction * map.s_scale * map.s_scale) {
    run.try_extra_starts(kRescueStarts, true);
    const double w = map.value(FitParameter::w, x.data());
    out.notices.push_back("w reached its bound 0 although the retract goes " + detail::short_number(-data.dip) +
                          " N below the baseline: refitted from " + std::to_string(kRescueStarts) + " more starts, w = " +
                          detail::short_number(w) + " J/m^2 after them");
  }
  detail::trim_held_to_model(reading, options, given_weights, data, ev, x, [&] { return run.resolve_in_place(); });
  if (options.baseline == Baseline::tilt) {
    run.detilt_baseline(&out);
    // The retract is read again on the detilted data, and the fit redone on what it decides.
    reading = detail::read_retract(data, options, force_span, hold_gradual_rise);
    data.sqrt_weight = given_weights;
    detail::apply_reading(reading, options, data);
    ev.invalidate();
    run.resolve_in_place();
    detail::trim_held_to_model(reading, options, given_weights, data, ev, x, [&] { return run.resolve_in_place(); });
  }
  run.record(&out);
  std::vector<bool> excluded = reading.tail;
  if (options.exclusion_sigmas == 0.0) excluded.assign(excluded.size(), false);
  out.excluded = excluded;
  out.excluded_count = static_cast<std::size_t>(std::count(excluded.begin(), excluded.end(), true));
  detail::assess_uncertainty(run, ev, map, x, options, data, &out);
  detail::explain_no_move(run, data, map, &out);
  out.baseline_offset = data.offset;
  if (data.offset != 0.0)
    out.notices.push_back("baseline offset " + detail::short_number(data.offset) + " N subtracted (the median of the " +
                          "samples at rest; P0 is not free): free P0 to fit it, or remove_offset = false "
                          "(--keep-offset) to keep the forces as they are");
  detail::diagnose_residuals(data, force_span, &out);
  detail::diagnose_indentation(data, &out);
  detail::record_model_notes(*model, data, force_span, &out);  // after the fit: a grid may refine
  for (const auto& note : model->notes_at(physical_at_x())) out.warnings.push_back(note);
  out.retract_release = detail::to_string(reading.release);
  out.pull_off_force = reading.pull_off.pull_off;  // the data's, whatever the fit did
  out.pull_off_baseline = reading.pull_off.baseline;
  out.pull_off_baseline_source = reading.pull_off.baseline_source;
  out.pull_off_baseline_measured = reading.pull_off.has_baseline;
  if (data.unloading_only)
    out.warnings.push_back("no baseline in the data: the contact region was found on the unloading samples before "
                           "the observed pull-off, the noise from their second differences" +
                           std::string(has(options, FitParameter::P0) ? ", and P0 started at 0" : ""));
  if (options.branch == Branch::approach && has(options, FitParameter::w))
    out.warnings.push_back("on approach the model snaps in at zero load, so w is identified only "
                           "through the shape of the loading curve; fit the retract branch for w");
  return out;
}

}  // namespace layerjkr
