// Internal: the adhesive law of a fit's curve, applied to a family's non-adhesive state in
// scalar or ceres::Jet arithmetic - JKR, the classical DMT, and Maugis-Dugdale on the half-space.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <boost/math/constants/constants.hpp>
#include <ceres/jet.h>

#include "adhesion/dmt_formula.hpp"
#include "adhesion/maugis_equations.hpp"
#include "core/scalar.hpp"
#include "fit_model.hpp"
#include "jkr/jkr_transform.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "layerjkr/types.hpp"
#include "models/state_formulas.hpp"

namespace layerjkr::detail {

// The JKR curve point of a non-adhesive state (the one transform, jkr_transform.hpp); the
// curve's adhesion parameter is s = sqrt(w).
template <int N>
void adhesive(const ceres::Jet<double, N>& a, const StateOf<ceres::Jet<double, N>>& h,
              const ceres::Jet<double, N>& s, ceres::Jet<double, N>* delta, ceres::Jet<double, N>* P) {
  jkr_from_state_sqrt_w(a, h.P_H, h.delta_H, h.S, h.dS_da, s, delta, P);
}
inline void adhesive(double a, const StateOf<double>& h, double s, double* delta, double* P) {
  jkr_from_state(a, h.P_H, h.delta_H, h.S, h.dS_da, s * s, delta, P);
}

// The adhesive law every family applies to its non-adhesive state: JKR, or the classical DMT
// (delta = delta_H, P = P_H - 2 pi w R) with R the varying paraboloid's or the tip's fixed
// 1/f''(0). (Maugis-Dugdale is not a transform of the state: HertzCurve solves it.)
struct StateLaw {
  AdhesionModel model = AdhesionModel::jkr;
  bool R_varies = false;  ///< DMT: R is CurveParameters::R (a paraboloid), else tip_radius
  double tip_radius = 0.0;

  template <class T>
  void apply(const T& a, const StateOf<T>& h, const CurveParameters<T>& p, T* delta, T* P) const {
    if (model == AdhesionModel::dmt) {
      *delta = h.delta_H;
      *P = dmt_force(h.P_H, T(p.s * p.s), R_varies ? p.R : T(tip_radius));
      return;
    }
    adhesive(a, h, p.s, delta, P);
  }
  // The fitted model's name: the medium's, prefixed by the law unless it is JKR (as
  // AdhesiveLaw::name()).
  std::string name(const std::string& medium) const {
    return model == AdhesionModel::jkr ? medium : std::string(to_string(model)) + " on " + medium;
  }
};

// Maugis-Dugdale for a paraboloid of radius R on a half-space of E*, in the dimensionless
// variables of maugis_equations.hpp. m's unknown s_m = sqrt(m^2 - 1) is solved in double (the
// library's maugis_point, then Newton to the last ulp); one Newton step on the first equation
// in T then carries its exact first derivatives in every parameter and in a (implicit function
// theorem: ds_m/dx = -(dF/dx)/(dF/ds_m) at the root). NaN where lambda leaves the range of
// the closed form, [1e-4, 1e4], or the solve fails: the fit's evaluator rejects such a step.
template <class T>
void maugis_curve(const T& a, const T& E_star, const T& w, const T& R, const T& sigma0, T* delta, T* P) {
  using std::cbrt;
  constexpr double pi = boost::math::constants::pi<double>();
  const T K = (4.0 / 3.0) * E_star;
  const T length = cbrt(pi * w * R * R / K);  // a = A length
  const T lambda = 2.0 * sigma0 * cbrt(R / (pi * w * K * K));
  const T A = a / length;
  const double lv = value_of(lambda), Av = value_of(A);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!(lv >= 1e-4 && lv <= 1e4) || !(Av > 0.0) || !std::isfinite(Av)) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  double sm;
  try {
    const double m = maugis_point(lv, Av).m;
    sm = std::sqrt((m - 1.0) * (m + 1.0));
  } catch (const Error&) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  // m - 1 loses digits as lambda grows: polish s_m on the first equation itself.
  using J = ceres::Jet<double, 1>;
  double slope = 0.0;
  for (int it = 0; it < 3; ++it) {
    const J F = maugis_residual(J(lv), maugis_terms(J(Av), J(sm, 0)));
    slope = F.v[0];
    if (!(slope > 0.0)) break;
    const double next = sm - F.a / slope;
    if (!(next > 0.0)) break;
    const bool done = std::abs(next - sm) <= 1e-15 * sm;
    sm = next;
    if (done) break;
  }
  if (!(slope > 0.0)) {
    *delta = T(nan);
    *P = T(nan);
    return;
  }
  const T s_m = T(sm) - maugis_residual(lambda, maugis_terms(A, T(sm))) / slope;
  const MaugisTerms<T> t = maugis_terms(A, s_m);
  *P = maugis_force(lambda, A, t) * (pi * w * R);
  *delta = maugis_approach(lambda, A, t) * (length * length / R);
}

}  // namespace layerjkr::detail
