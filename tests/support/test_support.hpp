// Shared helpers for the test suite: tolerances and a zoo of profiles.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/profile.hpp"

namespace test {

// The message of the InputError `f` throws; anything else propagates and fails the test.
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const layerjkr::InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

inline double rel_err(double value, double reference) {
  if (reference == 0.0) return std::abs(value);
  return std::abs(value - reference) / std::abs(reference);
}

struct NamedProfile {
  std::string name;
  layerjkr::ProfilePtr profile;
  std::vector<double> radii;  // admissible, away from table knots
};

// Sphere-like tip sampled into a table; knots every 2.5e-4 m for (R, 5e-3, 21), so the
// zoo's test radii (odd multiples of 1.25e-4) sit mid-segment.
layerjkr::ProfilePtr sampled_sphere_table(double R, double r_max, int n);

// Every profile kind, including an autodiff callable (built in test_support.cpp,
// because Boost 1.74's autodiff and finite_difference headers clash in one unit).
std::vector<NamedProfile> profile_zoo();

}  // namespace test
