// The cosine transform of the exact layer's symbol (kernel_transform.hpp).
#include "models/kernel_transform.hpp"

#include <gsl/gsl_errno.h>

#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

double cosine_transform(gsl_function fn, double sigma, const std::vector<double>& splits, double scale, int levels) {
  constexpr std::size_t kLimit = 4000;
  constexpr double kCutoff = 40.0;
  struct Workspace {
    gsl_integration_workspace* ws = gsl_integration_workspace_alloc(kLimit);
    ~Workspace() { gsl_integration_workspace_free(ws); }
  } w;
  std::vector<double> edges{0.0};
  for (double x : splits)
    if (x > 0.0 && x < kCutoff) edges.push_back(x);
  edges.push_back(kCutoff);
  sigma = std::abs(sigma);
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const double a = edges[i], b = edges[i + 1];
    double result = 0.0, abserr = 0.0;
    int status = GSL_SUCCESS;
    if (sigma == 0.0) {
      status = gsl_integration_qag(&fn, a, b, 1e-15 * scale, 1e-13, kLimit, GSL_INTEG_GAUSS41, w.ws, &result, &abserr);
    } else {
      gsl_integration_qawo_table* wf = gsl_integration_qawo_table_alloc(sigma, b - a, GSL_INTEG_COSINE, static_cast<std::size_t>(levels));
      status = gsl_integration_qawo(&fn, a, 1e-15 * scale, 1e-13, kLimit, w.ws, wf, &result, &abserr);
      gsl_integration_qawo_table_free(wf);
    }
    // The integral is O(1) and asked for to 1e-15, so QAWO may report that rounding stops it;
    // its error estimate says whether the result is still good enough to use.
    if (status == GSL_EROUND && abserr < 1e-13 * scale) status = GSL_SUCCESS;
    if (status != GSL_SUCCESS)
      throw NumericalError(std::string("layerjkr exact layer: kernel transform failed at sigma = ") +
                           format_double(sigma) + " on u in [" + format_double(a) + ", " + format_double(b) +
                           "] (" + gsl_strerror(status) + ", error estimate " + format_double(abserr) + ")");
    total += result;
  }
  return total;
}

}  // namespace layerjkr::detail
