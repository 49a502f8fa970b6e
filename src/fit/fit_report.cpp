// Option validation and the plain-text report of a fit.
#include <cmath>
#include <set>
#include <sstream>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "core/short_number.hpp"
#include "fit/data/contact_steps.hpp"

namespace layerjkr {

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
  if (cantilever_stiffness && !(*cantilever_stiffness > 0.0 && std::isfinite(*cantilever_stiffness)))
    throw DomainError(fn, "cantilever_stiffness [N/m]", *cantilever_stiffness,
                      "finite and > 0 (unset: the curve's own spring constant)");
  if (!(window_fraction > 0.0 && window_fraction <= 1.0))
    throw DomainError(fn, "window_fraction", window_fraction, "(0, 1]");
  detail::validate_contact_options(*this);
  if (force_noise && !(*force_noise > 0.0 && std::isfinite(*force_noise)))
    throw DomainError(fn, "force_noise [N]", *force_noise, "finite and > 0 (unset: estimated)");
  if (radius_noise && !(*radius_noise > 0.0 && std::isfinite(*radius_noise)))
    throw DomainError(fn, "radius_noise [m]", *radius_noise, "finite and > 0 (unset: estimated)");
  if (displacement_noise && !(*displacement_noise > 0.0 && std::isfinite(*displacement_noise)))
    throw DomainError(fn, "displacement_noise [m]", *displacement_noise, "finite and > 0 (unset: estimated)");
  if (displacement_noise && !errors_in_displacement)
    throw InputError("FitOptions: displacement_noise = " + detail::short_number(*displacement_noise) +
                     " m weighs the displacement's residuals, which only errors_in_displacement fits: set it too");
  std::set<FitParameter> bounded;
  for (const ParameterBound& b : bounds) {
    const std::string name = "bounds of " + std::string(to_string(b.parameter));
    if (!seen.count(b.parameter))
      throw InputError("FitOptions: " + name + ": the parameter is not free (a bound holds a fitted parameter in a "
                       "range; give a fixed one its value in the scene)");
    if (!bounded.insert(b.parameter).second) throw InputError("FitOptions: " + name + " given twice");
    if (std::isnan(b.lower) || std::isnan(b.upper) || !(b.lower < b.upper))
      throw DomainError(fn, name + " (lower end)", b.lower, "below the upper end " + detail::short_number(b.upper) +
                                                          ", neither NaN (an infinite end is no bound)");
  }
  if (!(exclusion_sigmas >= 0.0) || !std::isfinite(exclusion_sigmas))
    throw DomainError(fn, "exclusion_sigmas", exclusion_sigmas, "finite and >= 0 (0: keep every sample)");
}

double FitSummary::chi_square() const {
  return static_cast<double>(samples_fitted) * rms_residual * rms_residual;
}

double FitSummary::reduced_chi_square() const {
  const std::size_t k = parameters.size();
  return samples_fitted > k ? chi_square() / static_cast<double>(samples_fitted - k) : std::nan("");
}

double FitSummary::aic() const {
  const double n = static_cast<double>(samples_fitted), k = static_cast<double>(parameters.size());
  return n > k && chi_square() > 0.0 ? n * std::log(chi_square() / n) + 2.0 * k : std::nan("");
}

double FitSummary::bic() const {
  const double n = static_cast<double>(samples_fitted), k = static_cast<double>(parameters.size());
  return n > k && chi_square() > 0.0 ? n * std::log(chi_square() / n) + k * std::log(n) : std::nan("");
}

std::string FitSummary::brief_report() const {
  std::ostringstream o;
  o.precision(6);
  o << "layerjkr fit: " << (converged ? "converged" : "NOT converged") << " after " << iterations
    << " iterations (" << termination << ")\n";
  o << "  model " << model << " (" << to_string(family) << "), " << points << " samples, " << points_in_contact
    << " in contact, rms residual " << rms_residual << " N\n";
  if (samples_fitted > parameters.size())
    o << "  chi-square " << chi_square() << " N^2 over " << samples_fitted << " samples and " << parameters.size()
      << " free: reduced " << reduced_chi_square() << " N^2, AIC " << aic() << ", BIC " << bic() << "\n";
  if (baseline_slope != 0.0)
    o << "  baseline tilt " << baseline_slope << " +- " << baseline_slope_stderr
      << " N/m (from the samples off contact; the data were detilted)\n";
  if (baseline_offset != 0.0) o << "  baseline offset " << baseline_offset << " N subtracted (P0 not free)\n";
  if (std::isfinite(pull_off_force))
    o << "  measured pull-off " << pull_off_force << " N (the lowest retract force, from the baseline "
      << pull_off_baseline << " N: " << pull_off_baseline_source << ")\n";
  if (excluded_count > 0)
    o << "  excluded " << excluded_count << " retract samples after the release that had not "
      << "returned to the baseline (not JKR: peeling, necking, viscoelastic tail)\n";
  o << detail::contact_point_line(contact_point);
  if (std::isfinite(radius_noise))
    o << "  noise: P " << force_noise << " N (" << (force_noise_given ? "given" : "estimated") << "), a " << radius_noise
      << " m (" << (radius_noise_given ? "given" : "estimated") << "): each column's residuals weighed by its own noise\n";
  if (std::isfinite(displacement_noise))
    o << "  noise: P " << force_noise << " N (" << (force_noise_given ? "given" : "estimated") << "), delta "
      << displacement_noise << " m (" << (displacement_noise_given ? "given" : "estimated")
      << "): errors in both, each sample's residual its distance to the curve\n";
  if (!no_move_reason.empty()) o << "  did not move from the start: " << no_move_reason << "\n";
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    const ParameterEstimate& e = parameters[j];
    o << "  " << to_string(e.parameter);
    if (e.curve >= 0) o << " (curve " << e.curve + 1 << ")";
    o << " = " << e.value;
    if (std::isfinite(e.standard_error))
      o << " +- " << e.standard_error;
    else if (e.at_bound && std::isfinite(e.upper_bound))
      o << " (at its bound; < " << e.upper_bound << " at 95 %)";
    else
      o << " (no error bar)";
    if (!e.reason.empty()) o << "\n      " << e.reason;
    o << "\n";
  }
  // Three states: shown identifiable, shown not separable, or not decided (and why).
  o << "  identifiable: " << (identifiable ? "yes" : identifiability_known ? "no" : "unknown");
  if (!identifiable) o << " - " << identifiability_reason;
  o << "\n";
  for (const auto& w : warnings) o << "  warning: " << w << "\n";
  for (const auto& n : notices) o << "  note: " << n << "\n";
  return o.str();
}

double FitSummary::model_delta0() const {
  for (const ParameterEstimate& e : parameters)
    if (e.parameter == FitParameter::delta0) return e.value;
  return std::isfinite(contact_point.value) ? contact_point.value : 0.0;
}

std::string FitSummary::identifiability() const {
  if (identifiable) return "yes";
  return (identifiability_known ? "no: " : "unknown: ") + identifiability_reason;
}

}  // namespace layerjkr
