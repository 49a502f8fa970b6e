#include "layerjkr/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace layerjkr {

std::string format_double(double value) {
  // The shortest form that reads back as the same double: 0.49 is "0.49", not
  // "0.48999999999999999", and a value just outside a bound still shows the digits that put it there.
  // Whole numbers below 1e16 keep their digits ("1000", not "1e+03"), as a user types them.
  char buffer[40];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (!std::isfinite(value) || std::strtod(buffer, nullptr) == value) break;
  }
  const double magnitude = std::fabs(value);
  if (std::isfinite(value) && magnitude >= 1.0 && magnitude < 1e16)
    digits = std::max(digits, static_cast<int>(std::floor(std::log10(magnitude))) + 1);
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

DomainError::DomainError(const std::string& function, const std::string& parameter,
                         double value, const std::string& valid_range)
    : Error("layerjkr::" + function + ": " + parameter + " = " + format_double(value) +
            " is invalid; valid range: " + valid_range),
      parameter_(parameter),
      value_(value) {}

namespace detail {

void require_finite(const char* function, const char* parameter, double value) {
  if (!std::isfinite(value)) throw DomainError(function, parameter, value, "finite");
}

void require_positive(const char* function, const char* parameter, double value) {
  if (!std::isfinite(value) || !(value > 0.0))
    throw DomainError(function, parameter, value, "finite and > 0");
}

void require_non_negative(const char* function, const char* parameter, double value) {
  if (!std::isfinite(value) || !(value >= 0.0))
    throw DomainError(function, parameter, value, "finite and >= 0");
}

void require_in_open_interval(const char* function, const char* parameter, double value,
                              double lower, double upper) {
  if (!(value > lower && value < upper))
    throw DomainError(function, parameter, value,
                      "(" + format_double(lower) + ", " + format_double(upper) + ")");
}

}  // namespace detail
}  // namespace layerjkr
