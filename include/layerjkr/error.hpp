// layerjkr: errors thrown by the library.
//
// Every invalid input raises a layerjkr::Error (or a class derived from it) whose
// message names the function, the offending parameter, its value and the valid
// range, e.g.
//   "layerjkr::make_sphere: R = -1 is invalid; valid range: finite and > 0".
// Nothing is clipped or silently dropped, and no public function returns NaN for
// a valid input.
#pragma once

#include <stdexcept>
#include <string>

namespace layerjkr {

/// Base class of everything layerjkr throws.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// A numeric parameter outside its domain.
class DomainError : public Error {
 public:
  DomainError(const std::string& function, const std::string& parameter, double value,
              const std::string& valid_range);
  const std::string& parameter() const noexcept { return parameter_; }
  double value() const noexcept { return value_; }

 private:
  std::string parameter_;
  double value_;
};

/// Malformed input (scene file, table, command-line value). The message names the
/// key or column and the offending text.
class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(message) {}
};

/// A numerical method failed to meet its tolerance or to bracket a root.
class NumericalError : public Error {
 public:
  explicit NumericalError(const std::string& message) : Error(message) {}
};

/// Formats a double in the fewest significant digits (at most 17) that read back as the same
/// double: a message shows what the user wrote (0.49, not 0.48999999999999999).
std::string format_double(double value);

namespace detail {
// Validation helpers; `function` is the public entry point the user called.
void require_finite(const char* function, const char* parameter, double value);
void require_positive(const char* function, const char* parameter, double value);
void require_non_negative(const char* function, const char* parameter, double value);
void require_in_open_interval(const char* function, const char* parameter, double value,
                              double lower, double upper);
}  // namespace detail

}  // namespace layerjkr
