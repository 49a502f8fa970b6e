// layerjkr._core's instrument-file bindings (instrument.cpp): read_instrument and the random-access
// InstrumentReader. A file of its own so that module.cpp keeps to the library's answers.
#pragma once

#include <pybind11/pybind11.h>

namespace layerjkr::python {

/// Adds read_instrument(path, begin, end) and the class InstrumentReader to `m`.
void bind_instrument(pybind11::module_& m);

}  // namespace layerjkr::python
