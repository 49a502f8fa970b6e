// Internal: adaptive tanh-sinh quadrature split at known kinks.
//
// tanh-sinh converges double-exponentially for analytic integrands, tolerates
// integrable endpoint singularities (low power laws), and its error estimate (the
// difference between the last two refinement levels) is reliable, unlike the
// pessimistic Gauss-Kronrod estimate. The abscissa tables are built once.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <boost/math/quadrature/tanh_sinh.hpp>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

/// Relative tolerance requested from every default profile quadrature.
constexpr double kProfileQuadratureTolerance = 1e-13;

// One rule per thread: Boost 1.74's integrate() is not const and grows its level
// tables lazily, so a shared instance would be a data race.
inline boost::math::quadrature::tanh_sinh<double>& tanh_sinh_rule() {
  thread_local boost::math::quadrature::tanh_sinh<double> rule;
  return rule;
}

/// int_lo^hi g, split at the given interior points. Throws NumericalError if the
/// estimated error exceeds 1e-9 of the L1 norm or the result is not finite.
template <class G>
double integrate_split(G g, double lo, double hi, std::vector<double> cuts,
                       const char* function) {
  cuts.erase(std::remove_if(cuts.begin(), cuts.end(),
                            [&](double c) { return !(c > lo && c < hi); }),
             cuts.end());
  std::sort(cuts.begin(), cuts.end());
  cuts.insert(cuts.begin(), lo);
  cuts.push_back(hi);
  double sum = 0.0, error_sum = 0.0, l1_sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (!(cuts[i + 1] > cuts[i])) continue;
    double error = 0.0, l1 = 0.0;
    std::size_t levels = 0;
    try {
      sum += tanh_sinh_rule().integrate(g, cuts[i], cuts[i + 1], kProfileQuadratureTolerance,
                                        &error, &l1, &levels);
    } catch (const std::exception& e) {  // Boost's domain_error for a NaN integrand
      throw NumericalError(std::string("layerjkr::") + function + ": quadrature failed: " + e.what());
    }
    error_sum += error;
    l1_sum += l1;
  }
  if (!std::isfinite(sum) || error_sum > 1e-9 * l1_sum)
    throw NumericalError(std::string("layerjkr::") + function +
                         ": adaptive quadrature did not converge (estimated error " +
                         format_double(error_sum) + ", L1 norm " + format_double(l1_sum) +
                         "); a callable profile may be losing precision to cancellation - "
                         "write e.g. sqrt(r^2+b^2)-b as r^2/(sqrt(r^2+b^2)+b)");
  // Callers pass dimensionless variables (t = r/a, or an angle): tanh-sinh's endpoint
  // thresholds are absolute and stall on physical intervals such as [0, 1e-7 m].
  return sum;
}

}  // namespace layerjkr::detail
