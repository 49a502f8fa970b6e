// The report schema of `summary`, `curve` and `fit --out` (reports.hpp).
#include "reports.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"

namespace layerjkr::cli {
namespace {

using json = nlohmann::ordered_json;

// JSON has no infinity: a point the model misses is null, and the warning says why.
json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }


}  // namespace

json report_json(const FitSummary& s, Branch branch) {
  json j;
  j["converged"] = s.converged;
  j["termination"] = s.termination;
  j["iterations"] = s.iterations;
  j["model"] = s.model;
  j["family"] = to_string(s.family);
  j["branch"] = to_string(branch);
  // A joint fit's per-curve parameters are keyed "delta0[2]" (curve 2, counting from 1).
  const auto key = [](const ParameterEstimate& e) {
    return std::string(to_string(e.parameter)) + (e.curve >= 0 ? "[" + std::to_string(e.curve + 1) + "]" : "");
  };
  json params = json::object();
  for (const auto& e : s.parameters)
    params[key(e)] = {{"value", e.value},
                                      {"unit", unit_of(e.parameter)},
                                      {"stderr", finite_or_null(e.standard_error)},
                                      {"initial", e.initial},
                                      {"at_bound", e.at_bound},
                                      {"upper_bound", finite_or_null(e.upper_bound)},
                                      {"identifiable", e.identifiable},
                                      {"reason", e.reason}};
  j["parameters"] = params;
  json corr = json::object();
  for (std::size_t i = 0; i < s.parameters.size(); ++i) {
    json row = json::object();
    for (std::size_t k = 0; k < s.parameters.size(); ++k)
      row[key(s.parameters[k])] = finite_or_null(s.correlation[i][k]);
    corr[key(s.parameters[i])] = row;
  }
  j["correlation"] = corr;
  j["rms_residual"] = s.rms_residual;
  j["statistics"] = {{"samples_fitted", s.samples_fitted},
                     {"chi_square", finite_or_null(s.chi_square())},
                     {"reduced_chi_square", finite_or_null(s.reduced_chi_square())},
                     {"aic", finite_or_null(s.aic())},
                     {"bic", finite_or_null(s.bic())},
                     {"function_evaluations", s.function_evaluations}};
  j["excluded"] = s.excluded_count;
  j["pull_off_force"] = finite_or_null(s.pull_off_force);
  j["baseline_slope"] = s.baseline_slope;
  j["baseline_slope_stderr"] = s.baseline_slope_stderr;
  j["baseline_offset"] = s.baseline_offset;
  j["points"] = s.points;
  j["points_in_contact"] = s.points_in_contact;
  j["identifiable"] = s.identifiable;
  j["identifiability_known"] = s.identifiability_known;
  j["identifiability_reason"] = s.identifiability_reason;
  j["unidentifiable"] = s.unidentifiable;
  j["no_move_reason"] = s.no_move_reason;
  j["warnings"] = s.warnings;
  j["notices"] = s.notices;
  j["noise"] = std::isfinite(s.radius_noise) ? json{{"P", s.force_noise}, {"P_given", s.force_noise_given},
                                                    {"a", s.radius_noise}, {"a_given", s.radius_noise_given}}
               : std::isfinite(s.displacement_noise)
                   ? json{{"P", s.force_noise}, {"P_given", s.force_noise_given}, {"delta", s.displacement_noise},
                          {"delta_given", s.displacement_noise_given}}
                   : json(nullptr);
  const ContactPointReport& c = s.contact_point;
  j["contact_point"] = {{"method", to_string(c.method)},
                        {"value", finite_or_null(c.value)},
                        {"stderr", finite_or_null(c.standard_error)},
                        {"baseline", finite_or_null(c.baseline)},
                        {"range_reference", finite_or_null(c.range_reference)},
                        {"approach_samples", c.approach_samples},
                        {"samples_in_range", c.samples_in_range}};
  return j;
}

json provenance_record(const Scene& scene, const FitOptions& options, const CsvOptions& csv,
                       const std::vector<InputRecord>& inputs, const std::vector<std::string>& command_line) {
  json p = json::parse(provenance_json(scene, options, &csv, inputs));
  std::vector<std::string> args;
  args.reserve(command_line.size());
  for (const std::string& a : command_line) args.push_back(escape_bytes(a));  // JSON holds UTF-8 only
  p["command_line"] = args;
  return p;
}

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

json contact_json(const ContactSummary& s, const std::string& profile) {
  json j;
  j["model"] = s.model;
  j["profile"] = profile;
  j["w"] = s.w;
  j["adhesion_model"] = to_string(s.adhesion);
  auto opt = [](const std::optional<double>& v) { return v ? json(*v) : json(nullptr); };
  j["pull_off_force"] = s.pull_off ? json(s.pull_off->P) : json(nullptr);
  j["pull_off_radius"] = s.pull_off ? json(s.pull_off->a) : json(nullptr);
  j["pull_off_delta"] = s.pull_off ? json(s.pull_off->delta) : json(nullptr);
  j["zero_load_radius"] = opt(s.zero_load_radius);
  if (s.fixed_grips)
    j["fixed_grips_critical"] = {{"force", s.fixed_grips->P}, {"radius", s.fixed_grips->a}, {"delta", s.fixed_grips->delta}};
  else
    j["fixed_grips_critical"] = nullptr;
  return j;
}

namespace {
json adhesion_json(const std::optional<AdhesionCheck>& c) {
  if (!c) return nullptr;
  return {{"lambda", c->lambda},
          {"sigma0", c->sigma0},
          {"sigma0_assumed", c->sigma0_assumed},
          {"pull_off_error", c->pull_off_error},
          {"basis", c->basis}};
}
}  // namespace

json summary_json(const SummaryAnswer& a) {
  json j = contact_json(a.contact, a.profile);
  j["model_error_estimate"] = {{"pull_off_force", finite_or_null(a.error.pull_off_force)},
                               {"zero_load_radius", finite_or_null(a.error.zero_load_radius)},
                               {"reference", a.error.reference}};
  if (a.K) {
    j["K"] = *a.K;
    j[a.g_is_tension ? "T" : "G"] = a.G.value_or(0.0);
  }
  if (a.E_star) j["E_star"] = *a.E_star;
  j["adhesion_check"] = adhesion_json(a.adhesion);
  if (a.kinetic) {
    const KineticSummary& k = *a.kinetic;
    const auto point = [](const CriticalPoint& p) { return json{{"a", p.a}, {"P", p.P}, {"delta", p.delta}}; };
    json sweep = json::array();
    for (std::size_t i = 0; i < k.rates.size(); ++i)
      sweep.push_back({{"rate", k.rates[i]},
                       {"pull_off_force", std::isnan(k.pull_off_forces[i]) ? json(nullptr) : json(k.pull_off_forces[i])}});
    j["kinetic_pull_off"] = {{"drive", k.drive.describe()},
                             {"control", to_string(k.drive.control)},
                             {"rate", k.drive.rate},
                             {"rate_unit", k.drive.control == RetractControl::load ? "N/s" : "m/s"},
                             {"start_force", k.start_force},
                             {"pull_off_force", k.pull_off.P},
                             {"pull_off", point(k.pull_off)},
                             {"pull_off_time", k.pull_off_time},
                             {"separation_time", k.separation_time},
                             {"equilibrium_pull_off_force", k.equilibrium_pull_off.P},
                             {"equilibrium_separation", point(k.equilibrium_separation)},
                             {"rate_ratio", k.rate_ratio},
                             {"regime", k.regime()},
                             {"rate_dependence", sweep}};
  }
  if (a.choice)
    j["model_choice"] = {{"model", to_string(a.choice->model)},
                         {"estimated_error", a.choice->estimated_error},
                         {"tolerance", a.choice->tolerance}};
  j["warnings"] = a.warnings;
  j["notices"] = a.notices;
  return j;
}

std::string curve_csv(const CurveAnswer& c) {
  std::string out = "a,P,delta,P_H,delta_H,S,error_est,c\n";
  for (std::size_t i = 0; i < c.states.size(); ++i) {
    const AdhesiveState& s = c.states[i];
    out += format_double(s.a) + "," + format_double(s.P) + "," + format_double(s.delta) + "," +
           format_double(s.hertz.P_H) + "," + format_double(s.hertz.delta_H) + "," + format_double(s.hertz.S) + "," +
           format_double(c.error_estimate[i]) + "," + format_double(s.c) + "\n";
  }
  return out;
}

}  // namespace layerjkr::cli
