// Internal: the explicit transform (19) from the non-adhesive state to the JKR state,
// written once and used by jkr_transform (double) and by the fit (ceres::Jet):
//   delta = delta_H - u,  P = P_H - S u,  u = sqrt(4 pi w a / S')   (eqs. 16, 17).
// The Jet form factors u = sqrt(w) sqrt(4 pi a / S'), so that w = 0 is a regular point for
// derivatives in sqrt(w); the double form takes one square root.
#pragma once

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "core/scalar.hpp"

namespace layerjkr::detail {

/// delta and P after unloading the state by u = delta_1 - delta_2 (eq. 17) at stiffness S.
template <class T>
void unload_by(const T& P_H, const T& delta_H, const T& S, const T& u, T* delta, T* P) {
  *delta = delta_H - u;
  *P = P_H - S * u;
}

/// The transform for work of adhesion w >= 0; w = 0 returns the state bit for bit.
inline void jkr_from_state(double a, double P_H, double delta_H, double S, double dS_da, double w,
                           double* delta, double* P) {
  constexpr double pi = boost::math::constants::pi<double>();
  if (w == 0.0) {
    *delta = delta_H;
    *P = P_H;
    return;
  }
  unload_by(P_H, delta_H, S, std::sqrt(4.0 * pi * w * a / dS_da), delta, P);
}

/// The transform in s = sqrt(w) for Jets; s held at 0 (no sensitivity) skips the
/// adhesion terms.
template <int N>
void jkr_from_state_sqrt_w(const ceres::Jet<double, N>& a, const ceres::Jet<double, N>& P_H,
                           const ceres::Jet<double, N>& delta_H, const ceres::Jet<double, N>& S,
                           const ceres::Jet<double, N>& dS_da, const ceres::Jet<double, N>& s,
                           ceres::Jet<double, N>* delta, ceres::Jet<double, N>* P) {
  constexpr double pi = boost::math::constants::pi<double>();
  if (is_constant_zero(s)) {
    *delta = delta_H;
    *P = P_H;
    return;
  }
  unload_by(P_H, delta_H, S, s * sqrt(4.0 * pi * a / dS_da), delta, P);
}

}  // namespace layerjkr::detail
