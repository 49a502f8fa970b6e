// Internal: GSL's default error handler aborts the process; the library checks the status of
// every GSL call that can fail, so the handler is switched off once per process, here and
// nowhere else (why it is not part of a Context: include/layerjkr/context.hpp).
#pragma once

namespace layerjkr::detail {
// Idempotent and thread-safe; call before any GSL call whose status is checked.
void silence_gsl_errors();
}
