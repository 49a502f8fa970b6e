// Internal: what the formulas templated on the scalar need to know about it. The same
// formula runs on double (ContactModel::state) and on ceres::Jet (the fit's Jacobian),
// so each formula is written once.
#pragma once

#include <ceres/jet.h>

namespace layerjkr::detail {

inline double value_of(double x) { return x; }
template <int N>
double value_of(const ceres::Jet<double, N>& x) {
  return x.a;
}

/// True when x is exactly zero and carries no sensitivity: the terms it multiplies
/// vanish identically and are skipped (no 0 * inf from a rough profile's f'', no
/// adhesion terms while w is held at 0).
inline bool is_constant_zero(double x) { return x == 0.0; }
template <int N>
bool is_constant_zero(const ceres::Jet<double, N>& x) {
  return x.a == 0.0 && x.v.isZero();
}

/// g(x) for a scalar or Jet x, from g and g' at value_of(x): the chain rule for a
/// function that is only available in double.
inline double lift(double g, double /*dg*/, double /*x*/) { return g; }
template <int N>
ceres::Jet<double, N> lift(double g, double dg, const ceres::Jet<double, N>& x) {
  return ceres::Jet<double, N>(g) + dg * (x - ceres::Jet<double, N>(x.a));
}

}  // namespace layerjkr::detail
