// fit() step 4, for a free Dugdale stress: sigma0 lies between the JKR and DMT limits, which the
// data may not exclude - the checks that keep its error bar honest (fitting.md, "Adhesion models").
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "fit/run/fit_run.hpp"
#include "fit/run/fit_steps.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.141592653589793238462643383279502884;

// Maugis' lambda at which a free sigma0 is held to ask whether the data exclude JKR (large) or
// DMT (small): within the closed form's range [1e-4, 1e4] with room for the refit to move E and w,
// and close to the limits (pull-off within 1e-7 of JKR's, 3e-5 of DMT's).
constexpr double kJkrLimitLambda = 1e3;
constexpr double kDmtLimitLambda = 1e-3;

// The estimate of q in the summary (null if q was not free).
ParameterEstimate* estimate_of(FitSummary* out, FitParameter q) {
  for (auto& p : out->parameters)
    if (p.parameter == q) return &p;
  return nullptr;
}

}  // namespace

// Maugis' lambda of the half-space with the fitted E* and the tip's radius R; on a layer or a stack
// (the Dugdale family) E* is the top layer's and R the tip's 1/f''(0): the contact's own lambda
// differs by the layer's stiffening, but both are proportional to sigma0, which is all the
// limits below need (they sit 1e3 beyond the contact's range either way).
double maugis_lambda_at(const ParameterMap& map, const std::vector<double>& x) {
  CurveParameters<double> p;
  double d0 = 0.0, P0 = 0.0;
  map.physical(x.data(), &p, &d0, &P0);
  const double E_star = p.E / ((1.0 - map.fixed.nu) * (1.0 + map.fixed.nu));
  return 2.0 * p.sigma0 * std::cbrt(p.R / (kPi * p.s * p.s * (16.0 / 9.0) * E_star * E_star));
}

// A free sigma0 with an error bar is identifiable only if the data exclude both limits it lies
// between: holding it where the contact is JKR (or DMT), with the other parameters refitted, must
// raise the deviance beyond the one-sided 95 % point (as w's upper bound). Otherwise the error bar
// is a local curvature of a cost that stays flat out to the limit, and sigma0 has only a bound.
void check_sigma0_limits(FitRun& run, ResidualModel& ev, const ParameterMap& map, const std::vector<double>& x,
                         std::size_t residuals, FitSummary* out) {
  if (!map.is_free(FitParameter::sigma0)) return;
  ParameterEstimate* e = estimate_of(out, FitParameter::sigma0);
  if (!e || !e->identifiable) return;
  const double C = run.final_cost();
  const double dof = static_cast<double>(residuals - map.free.size());
  if (!(C > kNoiselessCost * dof)) return;  // noiseless data: the curvature is the whole story
  const double lambda = maugis_lambda_at(map, x);
  const double x_sigma0 = x[static_cast<std::size_t>(map.index(FitParameter::sigma0))];
  for (const auto& [limit, name] : {std::pair{kJkrLimitLambda, "JKR"}, std::pair{kDmtLimitLambda, "DMT"}}) {
    const double held = run.cost_with_held(FitParameter::sigma0, x_sigma0 + std::log(limit / lambda));
    const double deviance = std::isfinite(held) ? (held - C) * dof / C : kNaN;
    if (!std::isfinite(deviance))  // e.g. a layer's Dugdale zone at the DMT limit outgrows the solver's range
      out->warnings.push_back(std::string("sigma0's separability from the ") + name +
                              " limit was not tested: the fit with sigma0 held at lambda = " + short_number(limit) +
                              " could not be evaluated; its error bar is the local curvature only");
    if (std::isfinite(deviance) && deviance < kUpperBoundDeviance) {
      out->unidentifiable.push_back(std::string("sigma0 from the ") + name + " limit (holding it at lambda = " +
                                    short_number(limit) + " and refitting the others raises the deviance by " +
                                    short_number(deviance) + ", below the one-sided 95 % point " +
                                    short_number(kUpperBoundDeviance) + ")");
      e->identifiable = false;
      e->standard_error = kNaN;
      e->reason = "not separable: " + out->unidentifiable.back();
      break;
    }
  }
  if (!ev.evaluate(x.data(), true)) throw NumericalError("fit: the model cannot be evaluated at the solution");
}

// A free sigma0 that ran beyond a limit (lambda above kJkrLimitLambda or below kDmtLimitLambda,
// towards the closed form's bounds, where the covariance fails: the cost is flat there) is held
// where it stopped, so the others keep their error bars, and reported without one. Returns the
// limit's name, or nullptr when sigma0 is inside them (or not free, or w is at 0).
const char* hold_sigma0_at_limit(FitRun& run, const ParameterMap& map, const std::vector<double>& x) {
  if (!map.is_free(FitParameter::sigma0)) return nullptr;
  const double lambda = maugis_lambda_at(map, x);
  const char* name = lambda >= kJkrLimitLambda ? "JKR" : lambda <= kDmtLimitLambda ? "DMT" : nullptr;
  if (!name || !run.hold(FitParameter::sigma0, x[static_cast<std::size_t>(map.index(FitParameter::sigma0))]))
    return nullptr;
  return name;
}

void report_sigma0_at_limit(const char* limit, double lambda, FitSummary* out) {
  out->unidentifiable.push_back(std::string("sigma0 from the ") + limit + " limit (it ran to lambda = " +
                                short_number(lambda) + ", where the curve no longer depends on it)");
  ParameterEstimate* e = estimate_of(out, FitParameter::sigma0);
  e->identifiable = false;
  e->standard_error = kNaN;
  e->reason = "not separable: " + out->unidentifiable.back();
  out->warnings.push_back(std::string("sigma0 ran to the ") + limit + " limit (lambda = " + short_number(lambda) +
                          "): the data do not determine it; the other parameters and their error bars are from "
                          "the fit with sigma0 held there");
}

}  // namespace layerjkr::detail
