// layerjkr._core's instrument-file bindings (instrument.cpp): read_instrument and the random-access
// InstrumentReader. A file of its own so that module.cpp keeps to the library's answers.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

namespace layerjkr::python {

/// Adds read_instrument(path, begin, end) and the class InstrumentReader to `m`.
void bind_instrument(pybind11::module_& m);

/// A file name as Python names files: decoded as os.fsdecode does (UTF-8, bytes that are not
/// UTF-8 as lone surrogates), so that open() and os.fsencode() give back the very bytes.
pybind11::str file_name(const std::string& name);

/// Text that may echo bytes from a file (a message, a header value, a warning) as a str that
/// prints safely: printable() (text.hpp).
pybind11::str text(const std::string& s);
pybind11::list texts(const std::vector<std::string>& v);

}  // namespace layerjkr::python
