// Boost.Math's error handlers for the library: every root finder, quadrature and special function
// that fails (a root not bracketed, an iteration limit, a pole, an overflow) throws a
// layerjkr::NumericalError - an Error the CLI and Python report as such - instead of Boost's
// std::domain_error or evaluation_error, which reached users as "internal error".
//
// The library's translation units are compiled with BOOST_MATH_{DOMAIN,POLE,OVERFLOW,EVALUATION,
// INDETERMINATE_RESULT}_ERROR_POLICY=user_error (src/CMakeLists.txt, PRIVATE: consumers keep
// Boost's defaults); Boost declares the handlers and calls them, and they are defined here for
// the floating-point types the library uses.
#include <boost/math/policies/error_handling.hpp>

#include <sstream>
#include <string>

#include "layerjkr/error.hpp"

namespace boost::math::policies {
namespace {

// Boost's message with its %1% placeholders filled: the function's with the type, the
// message's with the value (as Boost's own throw_on_error formats them).
template <class T>
[[noreturn]] void fail(const char* kind, const char* function, const char* message, const T& val) {
  const auto fill = [](std::string s, const std::string& with) {
    for (std::size_t at = s.find("%1%"); at != std::string::npos; at = s.find("%1%", at + with.size()))
      s.replace(at, 3, with);
    return s;
  };
  std::ostringstream v;
  v.precision(17);
  v << val;
  const std::string type = sizeof(T) == sizeof(float) ? "float" : sizeof(T) == sizeof(double) ? "double" : "long double";
  throw layerjkr::NumericalError(std::string(kind) + " in " + fill(function ? function : "(unknown)", type) + ": " +
                                 fill(message ? message : "", v.str()));
}

}  // namespace

template <class T>
T user_domain_error(const char* function, const char* message, const T& val) {
  fail("numerical method failed (domain error)", function, message, val);
}
template <class T>
T user_pole_error(const char* function, const char* message, const T& val) {
  fail("numerical method failed (pole)", function, message, val);
}
template <class T>
T user_overflow_error(const char* function, const char* message, const T& val) {
  fail("numerical method failed (overflow)", function, message, val);
}
template <class T>
T user_evaluation_error(const char* function, const char* message, const T& val) {
  fail("numerical method failed", function, message, val);
}
template <class T>
T user_indeterminate_result_error(const char* function, const char* message, const T& val) {
  fail("numerical method failed (indeterminate result)", function, message, val);
}

#define LAYERJKR_BOOST_ERRORS(T)                                                    \
  template T user_domain_error<T>(const char*, const char*, const T&);              \
  template T user_pole_error<T>(const char*, const char*, const T&);                \
  template T user_overflow_error<T>(const char*, const char*, const T&);            \
  template T user_evaluation_error<T>(const char*, const char*, const T&);          \
  template T user_indeterminate_result_error<T>(const char*, const char*, const T&);
LAYERJKR_BOOST_ERRORS(float)
LAYERJKR_BOOST_ERRORS(double)
LAYERJKR_BOOST_ERRORS(long double)
#undef LAYERJKR_BOOST_ERRORS

}  // namespace boost::math::policies
