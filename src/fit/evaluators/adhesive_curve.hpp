// Internal: the adhesive law of a fit's curve, applied to a family's non-adhesive state in
// scalar or ceres::Jet arithmetic - JKR, the classical DMT, and Maugis-Dugdale on the half-space.
#pragma once

#include <string>

#include <ceres/jet.h>

#include "core/scalar.hpp"
#include "fit/evaluators/fit_model.hpp"
#include "jkr/jkr_transform.hpp"
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

// The classical DMT point of a non-adhesive state h for s = sqrt(w): delta = delta_H,
// P = dmt_force(P_H, w, R). Defined in adhesive_curve.cpp (double, Jet1..Jet8), as maugis_curve.
template <class T>
void dmt_point(const StateOf<T>& h, const T& s, const T& R, T* delta, T* P);

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
      dmt_point(h, p.s, R_varies ? p.R : T(tip_radius), delta, P);
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
// Defined in adhesive_curve.cpp for double and Jet1..Jet8, apart from the families: GCC inlines
// the JKR path's Jet arithmetic per translation unit, and every Jet-heavy function beside it
// made foundation fits slower (docs/benchmarks.md).
template <class T>
void maugis_curve(const T& a, const T& E_star, const T& w, const T& R, const T& sigma0, T* delta, T* P);

}  // namespace layerjkr::detail
