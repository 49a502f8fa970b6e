#include "core/gsl_support.hpp"

#include <gsl/gsl_errno.h>

namespace layerjkr::detail {
void silence_gsl_errors() {
  static const bool once = [] {
    gsl_set_error_handler_off();
    return true;
  }();
  (void)once;
}
}  // namespace layerjkr::detail
