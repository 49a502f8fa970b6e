// Internal: the explicit transform (19) from the non-adhesive state to the JKR state,
// written once and templated on the scalar (double for jkr_transform, ceres::Jet for
// the fit):
//   delta = delta_H - u,  P = P_H - S u,  u = sqrt(4 pi w a / S') = sqrt(w) sqrt(4 pi a / S').
// It is written in sqrt(w) so that w = 0 is a regular point for derivatives.
#pragma once

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "core/scalar.hpp"

namespace layerjkr::detail {

template <class T>
void jkr_from_state(const T& a, const T& P_H, const T& delta_H, const T& S, const T& dS_da,
                    const T& sqrt_w, T* delta, T* P) {
  using std::sqrt;
  constexpr double pi = boost::math::constants::pi<double>();
  if (is_constant_zero(sqrt_w)) {  // no adhesion: the state itself, bit for bit
    *delta = delta_H;
    *P = P_H;
    return;
  }
  const T unload = sqrt_w * sqrt(4.0 * pi * a / dS_da);  // delta_1 - delta_2, eq. (17)
  *delta = delta_H - unload;
  *P = P_H - S * unload;
}

}  // namespace layerjkr::detail
