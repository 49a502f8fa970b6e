// fit(): the model, the parameter map and the summary; the steps are in fit_data.cpp,
// retract_reading.cpp, fit_start.cpp, fit_run.cpp (the Ceres solves), fit_uncertainty.cpp and
// fit_second_readings.cpp.
#include "layerjkr/fit.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <memory>
#include <limits>

#include "fit/data/contact_steps.hpp"
#include "fit/run/fit_run.hpp"
#include "fit/run/fit_steps.hpp"
#include "fit/data/retract_reading.hpp"
#include "layerjkr/error.hpp"
#include "fit/in_time/time_fit.hpp"

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
    if (q == FitParameter::drag)
      throw InputError("fit: free parameter drag (the lever's hydrodynamic drag) is fitted in time, with a relaxing "
                       "medium (medium.viscoelastic) and the curve's times; elastic fits do not model it yet");
  for (FitParameter q : options.free)
    if (q == FitParameter::E_inf || q == FitParameter::tau || q == FitParameter::beta || q == FitParameter::v_star ||
        q == FitParameter::n || q == FitParameter::E_2 || q == FitParameter::tau_2)
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
                         FitParameter::E_inf, FitParameter::tau, FitParameter::beta, FitParameter::v_star, FitParameter::n,
                         FitParameter::E_2, FitParameter::tau_2})
    map.ref[static_cast<int>(q)] = map.fixed_value(q);
  // E_inf is fitted on a log scale around its reference: a scene's E_inf = 0 would pin it there.
  if (map.is_free(FitParameter::E_inf) && !(map.ref[static_cast<int>(FitParameter::E_inf)] > 0.0))
    map.ref[static_cast<int>(FitParameter::E_inf)] = 0.25 * map.ref[static_cast<int>(FitParameter::E)];
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

}  // namespace

FitSummary fit(const CurveData& curve, const Scene& scene, const FitOptions& options) {
  const auto t_begin = std::chrono::steady_clock::now();
  options.validate();
  curve.validate();
  if (!scene.profile) throw InputError("fit: the scene has no indenter profile");
  // An option that cannot apply is refused, not ignored: the user meant something by it.
  if (options.errors_in_displacement && !curve.a.empty())
    throw InputError(curve.source + ": errors_in_displacement (--displacement-noise) fits (delta, P) data by their "
                                    "distance to the curve; these data carry " +
                     std::string(curve.radius_only() ? "no displacement (P, a)" : "contact radii (delta, P, a), whose "
                                                       "own residuals already place each sample on the curve"));
  if (options.radius_noise && (curve.a.empty() || curve.radius_only()))
    throw InputError(curve.source + ": radius_noise (--radius-noise) weighs the radius column of delta,P,a data "
                                    "against the force's; these data have " +
                     std::string(curve.a.empty() ? "no contact radii" : "no displacement (P, a)"));
  if (options.force_noise && !options.errors_in_displacement && (curve.a.empty() || curve.radius_only()))
    throw InputError(curve.source + ": force_noise (--force-noise) weighs the force column against the radius's "
                                    "(delta,P,a data) or the displacement's (errors_in_displacement); these data have " +
                     std::string(curve.a.empty() ? "no contact radii and delta is taken as exact"
                                                 : "no displacement (P, a)"));
  const bool in_time = scene.medium.relaxation.kind != RelaxationLaw::Kind::elastic || scene.adhesion.kinetics;
  if (options.errors_in_displacement && in_time)
    throw InputError(curve.source + ": errors_in_displacement (--displacement-noise) is supported in elastic fits, not "
                                    "in fits in time (their samples follow the clock, not the curve)");
  if (in_time) {
    if (!options.bounds.empty())
      throw InputError(curve.source + ": bounds are supported in elastic fits, not yet in fits in time (the law's "
                                      "parameters keep their own domains: beta in [0.01, 0.95], tau > 0)");
    FitSummary out = detail::fit_in_time(curve, scene, options);
    detail::judge_plausibility(&out);
    out.solve_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_begin).count();
    return out;
  }
  if (options.branch == Branch::dwell || options.branch == Branch::approach_dwell)
    throw InputError(curve.source + ": the " + to_string(options.branch) + " branch is fitted in time: give the medium a "
                                    "relaxation law (medium.viscoelastic); an elastic model holds the force while the "
                                    "indenter rests");
  // An elastic model holds the force while the indenter rests: dwell samples are not its to fit.
  const CurveData data = curve.without_dwell();
  if (data.radius_only() && detail::steered_contact(options))
    throw InputError(data.source + ": (P, a) data have no displacement: no contact point to find and no indentation "
                                   "range to select (use contact_point fit and no ranges)");
  FitSummary out = detail::fit_once(data, scene, options, false);
  if (out.retract_release == detail::to_string(detail::Release::gradual)) out = detail::weigh_gradual_rise(data, scene, options, std::move(out));
  detail::judge_plausibility(&out);
  if (out.converged) detail::check_fixed_baseline(data, scene, options, &out);
  if (out.converged) detail::check_baseline_trade(data, scene, options, &out);
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
  detail::FitRun run(ev, map, options, data, x);
  // A start outside the model's domain is a data problem. With the Jacobian where Ceres' first
  // iteration asks for it at this point next (a linear fit needs the residuals only).
  if (!run.linear_candidate() && !ev.evaluate(x.data(), true)) ev.invalidate();
  if (!ev.evaluate(x.data(), false))
    throw InputError(curve.source + ": the model cannot be evaluated at the data-driven start "
                                    "(the indentation exceeds the model's range of radii)");

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
  // A parameter at an end of its range is the range's, not the data's: held there, the others
  // are assessed without it (FitOptions::bounds).
  const std::vector<detail::BoundHit> at_bounds = detail::at_user_bounds(map, options, x);
  if (!at_bounds.empty())
    run.hold(at_bounds.front().bound.parameter, x[static_cast<std::size_t>(map.index(at_bounds.front().bound.parameter))]);
  run.record(&out);
  std::vector<bool> excluded = reading.tail;
  if (options.exclusion_sigmas == 0.0) excluded.assign(excluded.size(), false);
  out.excluded = excluded;
  out.excluded_count = static_cast<std::size_t>(std::count(excluded.begin(), excluded.end(), true));
  detail::assess_uncertainty(run, ev, map, x, options, data, &out);
  detail::report_user_bounds(at_bounds, &out);
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
  detail::record_pull_off(reading.pull_off, &out);  // the data's, whatever the fit did
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
