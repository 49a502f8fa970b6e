// Internal: GSL's default error handler aborts the process; the library checks
// every GSL status itself, so the handler is switched off once.
#pragma once

namespace layerjkr::detail {
void silence_gsl_errors();
}
