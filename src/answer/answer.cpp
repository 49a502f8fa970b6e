// solve_summary and solve_curve (answer.hpp): the scene's model, its JKR solution and the
// judge of both, with the warnings the estimates call for.
#include "layerjkr/answer.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "layerjkr/adhesion_check.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr {
namespace {

std::string percent(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g %%", 100.0 * x);
  return buf;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The last line of defence: an answer never carries a non-finite number silently. Inputs
// are range-checked (scene_reader's check_scales), so a non-finite value here is a solver
// failure, reported as one instead of printed as inf or NaN.
void require_finite(const std::string& what, double v) {
  if (!std::isfinite(v))
    throw NumericalError("the answer's " + what + " is " + format_double(v) +
                         " (not finite): the solver failed for this scene; please report it");
}

void require_finite(const std::string& what, const CriticalPoint& p) {
  require_finite(what + " radius", p.a);
  require_finite(what + " force", p.P);
  require_finite(what + " approach", p.delta);
}

void require_finite(const ContactSummary& c) {
  if (c.zero_load_radius) require_finite("zero-load radius", *c.zero_load_radius);
  if (c.pull_off) require_finite("pull-off", *c.pull_off);
  if (c.fixed_grips) require_finite("fixed-grips critical", *c.fixed_grips);
}

// An unbounded error estimate is a finding (a missed critical point), reported by a
// warning; NaN is not.
void require_not_nan(const std::string& what, double v) {
  if (std::isnan(v)) require_finite(what, v);
}

// The scene's adhesive law on its built model.
AdhesiveSolution adhesive_solution(const Scene& scene, const BuiltScene& built) {
  return AdhesiveSolution(make_adhesive_law(built.model, built.resolved.spec, scene.w, scene.adhesion));
}

// The contact's JKR solution: the answer's own, or one beside it (the adhesion check's lambda
// and the model error estimate are judged on it).
AdhesiveSolution jkr_solution(const BuiltScene& built, const AdhesiveSolution& solution) {
  return solution.law().model() == AdhesionModel::jkr ? solution : AdhesiveSolution(built.model, solution.w());
}

// The adhesion check, and its warning when the answer's adhesion model is off Maugis-Dugdale
// by more than the threshold.
std::optional<AdhesionCheck> checked_adhesion(const Scene& scene, const BuiltScene& built, const AdhesiveSolution& jkr,
                                              const AdhesiveSolution& answer, const AnswerOptions& options,
                                              std::vector<std::string>* warnings) {
  // Maugis-Dugdale is solved on the medium only where the scene's model solves it exactly: a
  // thin-layer law's answer would mix its own model error into the adhesion check's.
  const ModelSpec* medium = built.reference || built.choice ? nullptr : &built.resolved.spec;
  std::optional<AdhesionCheck> c = check_adhesion(jkr, answer, scene.adhesion, medium);
  if (!c) return c;
  require_not_nan("adhesion check's lambda", c->lambda);
  require_not_nan("adhesion check's pull-off error", c->pull_off_error);
  if (c->pull_off_error > options.warning_threshold)
    warnings->push_back(std::string(c->model == AdhesionModel::jkr ? "JKR" : "DMT") +
                        " is outside its range here: " + c->brief_report() +
                        "; adhesion.model \"maugis_dugdale\" solves the transition");
  return c;
}

// The retract of options.retract with the scene's kinetics, and the sweep of rates around it.
KineticSummary kinetic_summary(const Scene& scene, const BuiltScene& built, const AnswerOptions& options) {
  KineticRetractOptions o;
  o.drive = *options.retract;
  o.start_force = options.retract_start_force;
  const KineticRetract r = kinetic_retract(built.model, scene.w, *scene.adhesion.kinetics, o);
  KineticSummary k;
  k.drive = o.drive;
  k.start_force = o.start_force;
  k.pull_off = r.pull_off;
  k.pull_off_time = r.pull_off_time;
  k.separation_time = r.separation_time;
  k.equilibrium_pull_off = r.equilibrium_pull_off;
  k.equilibrium_separation = r.equilibrium_separation;
  k.rate_ratio = r.rate_ratio;
  k.at_equilibrium = r.at_equilibrium;
  for (double f : {0.01, 0.1, 1.0, 10.0, 100.0}) k.rates.push_back(f * o.drive.rate);
  k.pull_off_forces = kinetic_pull_off_forces(built.model, scene.w, *scene.adhesion.kinetics, o, k.rates);
  return k;
}

}  // namespace

void AnswerOptions::validate() const {
  detail::require_in_open_interval("AnswerOptions", "warning_threshold", warning_threshold, 0.0, 1.0);
  if (retract) retract->validate();
  detail::require_finite("AnswerOptions", "retract_start_force", retract_start_force);
}

SummaryAnswer solve_summary(const Scene& scene, const AnswerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.validate();
  BuiltScene built = build_scene_for_summary(scene);
  const AdhesiveSolution solution = adhesive_solution(scene, built);
  const AdhesiveSolution jkr = jkr_solution(built, solution);
  SummaryAnswer s;
  s.contact = summarize(solution);
  // The model error is the medium model's, judged on the JKR summary for every adhesion model.
  s.error = error_estimator(scene, built).summary(scene.adhesion.model == AdhesionModel::jkr ? s.contact
                                                                                           : summarize(jkr));
  s.profile = scene.profile->describe();
  s.K = built.resolved.K;
  s.G = built.resolved.G;
  s.g_is_tension = built.resolved.g_is_tension;
  s.E_star = built.resolved.E_star;
  s.choice = built.choice;
  s.warnings = std::move(built.resolved.warnings);
  s.notices = std::move(built.resolved.notices);
  if (!std::isfinite(s.error.worst()))
    s.warnings.push_back("model '" + s.contact.model + "' misses a critical point its reference model '" +
                         s.error.reference + "' has (estimated error unbounded)");
  else if (s.error.worst() > options.warning_threshold)
    s.warnings.push_back("model '" + s.contact.model + "' is estimated " + percent(s.error.pull_off_force) +
                         " off its reference model '" + s.error.reference + "' in the pull-off force and " +
                         percent(s.error.zero_load_radius) + " in the zero-load radius");
  s.adhesion = checked_adhesion(scene, built, jkr, solution, options, &s.warnings);
  if (options.retract && !scene.adhesion.kinetics)
    throw InputError("summary: a retract rate (" + options.retract->describe() + ") changes nothing without "
                     "adhesion.kinetics in the scene: its adhesion is at equilibrium");
  if (scene.adhesion.kinetics && options.retract) {
    s.kinetic = kinetic_summary(scene, built, options);
    require_finite("rate-dependent pull-off", s.kinetic->pull_off);
  } else if (scene.adhesion.kinetics) {
    s.notices.push_back("the adhesion has kinetics (" + scene.adhesion.kinetics->describe() + "): the critical points "
                        "are at equilibrium, the slow-retract limit; give a retract rate for the rate-dependent pull-off");
  }
  require_finite(s.contact);
  require_not_nan("pull-off force error estimate", s.error.pull_off_force);
  require_not_nan("zero-load radius error estimate", s.error.zero_load_radius);
  for (const std::optional<double>& x : {s.K, s.G, s.E_star})
    if (x) require_finite("model constant", *x);
  s.seconds = seconds_since(start);
  return s;
}

CurveAnswer solve_curve(const Scene& scene, const std::vector<double>& radii, const AnswerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.validate();
  if (radii.empty()) throw InputError("curve: give at least one contact radius");
  for (double a : radii)
    if (!(a > 0.0) || !std::isfinite(a))
      throw InputError("contact radius a = " + format_double(a) + " is invalid; valid range: finite and > 0 [m]");
  BuiltScene built = build_scene_for_radii(scene, radii);
  const AdhesiveSolution solution = adhesive_solution(scene, built);
  // Bounded before any state is solved: what a radius costs times how many were asked for.
  if (const std::size_t most = solution.law().max_curve_radii(); most > 0 && radii.size() > most)
    throw InputError("curve: " + std::to_string(radii.size()) + " radii of " + solution.law().name() + " (" +
                     solution.law().radius_cost() + " a radius) exceed its limit of " + std::to_string(most) +
                     " radii a call (docs/development.md, Limits): ask fewer radii, or split them over several calls");
  const ModelErrorEstimator estimator = error_estimator(scene, built);
  CurveAnswer c;
  c.error_estimate = estimator.along(radii);
  c.states = solution.curve(radii);
  c.model = solution.law().name();
  c.reference = estimator.reference_name();
  c.choice = built.choice;
  c.warnings = std::move(built.resolved.warnings);
  c.notices = std::move(built.resolved.notices);
  c.adhesion = checked_adhesion(scene, built, jkr_solution(built, solution), solution, options, &c.warnings);
  double worst = 0.0, worst_a = 0.0;
  for (std::size_t i = 0; i < c.states.size(); ++i) {
    const std::string at = " at a = " + format_double(c.states[i].a) + " m";
    require_finite("force" + at, c.states[i].P);
    require_finite("approach" + at, c.states[i].delta);
    require_not_nan("error estimate" + at, c.error_estimate[i]);
    if (c.error_estimate[i] > worst) worst = c.error_estimate[i], worst_a = c.states[i].a;
  }
  if (worst > options.warning_threshold)
    c.warnings.push_back("model '" + c.model + "' is estimated " + percent(worst) + " off its reference model '" +
                         c.reference + "' at a = " + format_double(worst_a) + " m (column error_est)");
  c.seconds = seconds_since(start);
  return c;
}

}  // namespace layerjkr
