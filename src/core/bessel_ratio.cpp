#include "core/bessel_ratio.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_sf_bessel.h>

#include <cmath>

#include "core/gsl_support.hpp"
#include "layerjkr/error.hpp"

namespace layerjkr::detail {

double bessel_k1_over_k0(double x) {
  silence_gsl_errors();
  if (!(x > 0.0) || !std::isfinite(x))
    throw DomainError("bessel_k1_over_k0", "x", x, "finite and > 0");
  if (x > 1e8) return 1.0 + 0.5 / x;  // asymptotic; scaled GSL values lose accuracy there
  gsl_sf_result k0, k1;
  if (gsl_sf_bessel_K0_scaled_e(x, &k0) != GSL_SUCCESS ||
      gsl_sf_bessel_K1_scaled_e(x, &k1) != GSL_SUCCESS)
    throw NumericalError("layerjkr: GSL failed to evaluate K0, K1 at x = " + format_double(x));
  return k1.val / k0.val;
}

}  // namespace layerjkr::detail
