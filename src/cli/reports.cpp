// The curve and summary answers shared by the CLI and the Python module (reports.hpp).
#include "reports.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/model_error.hpp"
#include "summary_json.hpp"

namespace layerjkr::cli {
namespace {

std::string percent(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g %%", 100.0 * x);
  return buf;
}

std::string choice_note(const BuiltScene& built, const std::string& judged_at) {
  if (!built.automatic) return "";
  return "auto chose model '" + built.chosen_model + "' (estimated error " + format_double(built.estimated_error) + " " +
         judged_at + ")";
}

}  // namespace

std::vector<double> parse_radii(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const char* begin = item.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (item.empty() || end == begin || *end != '\0' || errno == ERANGE || !std::isfinite(v))
      throw InputError("--at: '" + item + "' is not a finite number");
    if (!(v > 0.0)) throw InputError("--at: contact radius " + item + " must be > 0");
    out.push_back(v);
  }
  if (out.empty()) throw InputError("--at: give at least one contact radius");
  return out;
}

CurveTable curve_table(const Scene& scene, const std::vector<double>& radii) {
  for (double a : radii)
    if (!(a > 0.0) || !std::isfinite(a))
      throw InputError("contact radius a = " + format_double(a) + " is invalid; valid range: finite and > 0 [m]");
  BuiltScene built = build_scene_for_radii(scene, radii);
  const JkrSolution solution(built.model, scene.w);
  const ModelErrorEstimator estimator = error_estimator(scene, built);
  CurveTable t;
  t.error_est = estimator.along(radii);
  t.states = solution.curve(radii);
  double worst = 0.0, worst_a = 0.0;
  for (std::size_t i = 0; i < t.states.size(); ++i)
    if (t.error_est[i] > worst) worst = t.error_est[i], worst_a = t.states[i].a;
  if (worst > kWarnError)
    built.warnings.push_back("model '" + built.model->name() + "' is estimated " + percent(worst) +
                             " off its reference model '" + estimator.reference_name() +
                             "' at a = " + format_double(worst_a) + " m (column error_est)");
  t.warnings = built.warnings;
  t.choice_note = choice_note(built, "over the curve's radii");
  return t;
}

SummaryReport summary_report(const Scene& scene) {
  BuiltScene built = build_scene_for_summary(scene);
  const JkrSolution solution(built.model, scene.w);
  const ContactSummary s = summarize(solution);
  const SummaryError error = error_estimator(scene, built).summary(s);
  nlohmann::ordered_json j = summary_json(s, scene.profile->describe());
  // JSON has no infinity: a point the model misses is null, and the warning says why.
  auto finite_or_null = [](double x) { return std::isfinite(x) ? nlohmann::ordered_json(x) : nullptr; };
  j["model_error_estimate"] = {{"pull_off_force", finite_or_null(error.pull_off_force)},
                               {"zero_load_radius", finite_or_null(error.zero_load_radius)},
                               {"reference", error.reference}};
  if (built.has_foundation_constants) {
    j["K"] = built.K;
    j[scene.medium.type == MediumType::filonenko_borodich ? "T" : "G"] = built.G;
  }
  if (built.has_effective_modulus) j["E_star"] = built.E_star;
  if (built.automatic)
    j["model_choice"] = {{"model", built.chosen_model}, {"estimated_error", built.estimated_error}, {"tolerance", scene.tolerance}};
  if (!std::isfinite(error.worst()))
    built.warnings.push_back("model '" + s.model + "' misses a critical point its reference model '" + error.reference +
                             "' has (estimated error unbounded)");
  else if (error.worst() > kWarnError)
    built.warnings.push_back("model '" + s.model + "' is estimated " + percent(error.pull_off_force) +
                             " off its reference model '" + error.reference + "' in the pull-off force and " +
                             percent(error.zero_load_radius) + " in the zero-load radius");
  j["warnings"] = built.warnings;
  return {j, built.warnings, choice_note(built, "at the pull-off and zero-load point")};
}

}  // namespace layerjkr::cli
