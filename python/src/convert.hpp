// layerjkr._core's conversions between numpy arrays and the library's vectors, shared by the
// binding files (module.cpp, fit_summary.cpp, batch.cpp): arrays come in as float64 (converted if
// needed) and go out as new arrays.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"

namespace layerjkr::python {

using Array = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;
/// Segment labels: a numpy int64 array passes without a Python object per sample.
using Labels = pybind11::array_t<std::int64_t, pybind11::array::c_style | pybind11::array::forcecast>;

/// A 1-D array's values; InputError naming `name` for any other shape.
inline std::vector<double> to_vector(const Array& a, const char* name) {
  if (a.ndim() != 1)
    throw InputError(std::string(name) + " must be a 1-D array; got " + std::to_string(a.ndim()) + " dimensions");
  return std::vector<double>(a.data(), a.data() + a.size());
}

inline pybind11::array_t<double> to_array(const std::vector<double>& v) {
  pybind11::array_t<double> out(static_cast<pybind11::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

inline pybind11::array_t<bool> to_bool_array(const std::vector<bool>& v) {
  pybind11::array_t<bool> out(static_cast<pybind11::ssize_t>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) out.mutable_data()[i] = v[i];
  return out;
}

}  // namespace layerjkr::python
