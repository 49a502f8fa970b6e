#include "layerjkr/error.hpp"

#include <cmath>
#include <cstdio>

namespace layerjkr {

std::string format_double(double value) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
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
