// libFuzzer target: the curve CSV reader. The first byte picks units, the raw-AFM
// options, a curve and a row limit; any input must parse to finite, equal-length columns or throw layerjkr::Error.
#include <cmath>
#include <cstdint>
#include <string>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  layerjkr::CsvOptions o;
  const std::uint8_t mode = data[0];
  if (mode & 1) o.length_unit = 1e-9;
  if (mode & 2) o.force_unit = 1e-9;
  if (mode & 4) o.spring_constant = 0.05;
  if (mode & 8) o.z_sign = -1.0;
  if (mode & 16) o.curve = 3;     // the curve column's selection
  if (mode & 32) o.max_rows = 5;  // the row limit
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const layerjkr::CurveData c = layerjkr::parse_curve_csv(text, "fuzz", o);
    if (c.P.size() != c.delta.size()) __builtin_trap();
    for (std::size_t i = 0; i < c.size(); ++i)
      if (!std::isfinite(c.delta[i]) || !std::isfinite(c.P[i])) __builtin_trap();
    for (layerjkr::Branch b : {layerjkr::Branch::approach, layerjkr::Branch::retract, layerjkr::Branch::all})
      for (std::size_t i : c.select(b))
        if (i >= c.size()) __builtin_trap();
  } catch (const layerjkr::Error&) {
  }
  return 0;
}
