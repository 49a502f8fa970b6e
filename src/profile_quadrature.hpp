// Internal: adaptive Gauss-Kronrod quadrature split at known kinks.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

/// Relative tolerance of every default profile quadrature.
constexpr double kProfileQuadratureTolerance = 1e-13;

/// int_lo^hi g, split at the given interior points; throws NumericalError if the
/// Gauss-Kronrod error estimate exceeds 1e-10 of the L1 norm or the result is not finite.
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
    double error = 0.0, l1 = 0.0;
    sum += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        g, cuts[i], cuts[i + 1], 20, kProfileQuadratureTolerance, &error, &l1);
    error_sum += error;
    l1_sum += l1;
  }
  if (!std::isfinite(sum) || error_sum > 1e-10 * l1_sum)
    throw NumericalError(std::string("layerjkr::") + function +
                         ": adaptive quadrature did not converge (estimated error " +
                         format_double(error_sum) + ", L1 norm " + format_double(l1_sum) + ")");
  return sum;
}

}  // namespace layerjkr::detail
