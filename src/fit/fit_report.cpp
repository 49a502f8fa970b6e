// Names, option validation and the plain-text report of a fit.
#include <cmath>
#include <set>
#include <sstream>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"

namespace layerjkr {

const char* to_string(FitParameter p) {
  switch (p) {
    case FitParameter::K: return "K";
    case FitParameter::G: return "G";
    case FitParameter::w: return "w";
    case FitParameter::delta0: return "delta0";
    case FitParameter::P0: return "P0";
    case FitParameter::E: return "E";
    case FitParameter::R: return "R";
  }
  return "?";
}

FitParameter parse_fit_parameter(const std::string& name, const std::string& what) {
  for (FitParameter p : {FitParameter::K, FitParameter::G, FitParameter::w, FitParameter::delta0,
                         FitParameter::P0, FitParameter::E, FitParameter::R})
    if (name == to_string(p)) return p;
  if (name == "T") return FitParameter::G;  // Filonenko-Borodich tension plays G's role
  throw InputError(what + ": '" + name + "' is not a fit parameter (known: K, G or T, w, delta0, P0, E, R)");
}

std::vector<FitParameter> parse_fit_parameters(const std::string& list, const std::string& what) {
  std::vector<FitParameter> out;
  std::set<FitParameter> seen;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    const FitParameter p = parse_fit_parameter(item, what);
    if (!seen.insert(p).second) throw InputError(what + ": '" + item + "' is listed twice");
    out.push_back(p);
  }
  if (out.empty()) throw InputError(what + ": give at least one parameter (e.g. E,w,delta0)");
  return out;
}

void FitOptions::validate() const {
  const char* fn = "FitOptions";
  if (free.empty()) throw DomainError(fn, "free (number of free parameters)", 0.0, ">= 1");
  std::set<FitParameter> seen(free.begin(), free.end());
  if (seen.size() != free.size())
    throw DomainError(fn, "free (a parameter listed twice; count)", static_cast<double>(free.size()),
                      "distinct parameters");
  if (loss != LossType::none && !(loss_scale > 0.0 && std::isfinite(loss_scale)))
    throw DomainError(fn, "loss_scale [N]", loss_scale, "finite and > 0 for huber and cauchy losses");
  if (max_iterations < 1) throw DomainError(fn, "max_iterations", max_iterations, ">= 1");
  detail::require_positive(fn, "function_tolerance", function_tolerance);
  detail::require_positive(fn, "parameter_tolerance", parameter_tolerance);
  detail::require_positive(fn, "gradient_tolerance", gradient_tolerance);
  if (extra_starts < 0 || extra_starts > 100)
    throw DomainError(fn, "extra_starts", extra_starts, "0 .. 100");
  detail::require_in_open_interval(fn, "correlation_limit", correlation_limit, 0.0, 1.0);
  if (table_points_per_decade < 8 || table_points_per_decade > 1000)
    throw DomainError(fn, "table_points_per_decade", table_points_per_decade, "8 .. 1000");
  if (cantilever_stiffness < 0.0)
    throw DomainError(fn, "cantilever_stiffness [N/m]", cantilever_stiffness,
                      ">= 0 (0: load control, inf: fixed grips, NaN: the curve's own)");
  if (!(window_fraction > 0.0 && window_fraction <= 1.0))
    throw DomainError(fn, "window_fraction", window_fraction, "(0, 1]");
  if (!(exclusion_sigmas >= 0.0) || !std::isfinite(exclusion_sigmas))
    throw DomainError(fn, "exclusion_sigmas", exclusion_sigmas, "finite and >= 0 (0: keep every sample)");
}

std::string FitSummary::brief_report() const {
  std::ostringstream o;
  o.precision(6);
  o << "layerjkr fit: " << (converged ? "converged" : "NOT converged") << " after " << iterations
    << " iterations (" << termination << ")\n";
  o << "  model " << model << " (" << family << "), " << points << " samples, " << points_in_contact
    << " in contact, rms residual " << rms_residual << " N\n";
  if (baseline_slope != 0.0)
    o << "  baseline tilt " << baseline_slope << " +- " << baseline_slope_stderr
      << " N/m (from the samples off contact; the data were detilted)\n";
  if (excluded_count > 0)
    o << "  excluded " << excluded_count << " retract samples after the model's jump that had not "
      << "returned to the baseline (not JKR: peeling, necking, viscoelastic tail)\n";
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    const ParameterEstimate& e = parameters[j];
    o << "  " << to_string(e.parameter) << " = " << e.value;
    if (std::isfinite(e.standard_error))
      o << " +- " << e.standard_error;
    else if (e.at_bound)
      o << " (at its bound)";
    else if (!e.identifiable)
      o << " (no error bar: not identifiable)";
    else
      o << " (no error bar: covariance not computed)";
    o << "\n";
  }
  o << "  identifiable: " << (identifiable ? "yes" : "no") << "\n";
  for (const auto& u : unidentifiable) o << "    cannot separate: " << u << "\n";
  for (const auto& w : warnings) o << "  warning: " << w << "\n";
  return o.str();
}

}  // namespace layerjkr
