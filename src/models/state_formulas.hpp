// Internal: the non-adhesive state of the closed-form models, written once and templated
// on the scalar. ContactModel::state runs them on double; the fit runs them on
// ceres::Jet so that the Jacobian in K, G, E, R and a comes from the same lines.
// (jkr.cpp keeps the paper's explicit forms (42), (50)-(51) separately, as the
// independent check the tests compare these against.)
#pragma once

#include <cmath>

#include <boost/math/constants/constants.hpp>

#include "core/bessel_ratio.hpp"
#include "core/scalar.hpp"

namespace layerjkr::detail {

/// The profile at the contact radius: f(a), f'(a), f''(a) and M(a) = int_0^a f r dr.
template <class T>
struct ProfileAt {
  T f, df, d2f, M;
};

/// P_H [N], delta_H [m], S = dP_H/d delta_H [N/m] and S' = dS/da [N/m^2].
template <class T>
struct StateOf {
  T P_H, delta_H, S, dS_da;
};

/// Two-term thin layer p = K w - G lap w inside the contact with p(a) = 0 (eqs. (43)-(45)
/// with the corrected force, docs/theory.md s.1); G = 0 is Winkler, eq. (41), exactly.
template <class T>
StateOf<T> two_term_state(const T& a, const ProfileAt<T>& g, const T& K, const T& G) {
  constexpr double pi = boost::math::constants::pi<double>();
  StateOf<T> s;
  const T bracket = a * a * g.f - 2.0 * g.M;  // = int_0^a r^2 f'(r) dr >= 0
  s.S = pi * K * a * a;
  s.dS_da = 2.0 * pi * K * a;
  if (is_constant_zero(G)) {  // Winkler: no 0 * inf from f''(a) of a rough profile
    s.delta_H = g.f;
    s.P_H = pi * K * bracket;
  } else {
    s.delta_H = g.f - (G / K) * (g.d2f + g.df / a);
    s.P_H = pi * K * bracket + pi * G * a * (g.df - a * g.d2f);
  }
  return s;
}

/// two_term_state for a paraboloid f = r^2/(2R) in closed form: the G-terms cancel in P_H
/// and shift delta_H by -2G/(KR) (docs/theory.md s.1). The fit uses it so that R can vary
/// and the Jacobian costs few operations; a test checks it against two_term_state.
template <class T>
StateOf<T> two_term_paraboloid_state(const T& a, const T& R, const T& K, const T& G) {
  constexpr double pi = boost::math::constants::pi<double>();
  const T a2 = a * a;
  StateOf<T> s;
  s.delta_H = (0.5 * a2 - 2.0 * G / K) / R;
  s.P_H = 0.25 * pi * K * a2 * a2 / R;
  s.S = pi * K * a2;
  s.dS_da = 2.0 * pi * K * a;
  return s;
}

/// Full Pasternak (or Filonenko-Borodich, G = T) foundation on the whole plane with the
/// decaying exterior w = c K0(lam r)/K0(lam a), lam = sqrt(K/G); slope continuity at the
/// free boundary fixes delta_H (docs/theory.md s.3). G > 0; lambda = sqrt(K/G), passed in
/// so that a model with fixed constants computes it once.
template <class T>
StateOf<T> full_foundation_state(const T& a, const ProfileAt<T>& g, const T& K, const T& G, const T& lambda) {
  constexpr double pi = boost::math::constants::pi<double>();
  const T x = lambda * a;
  const double xv = value_of(x);
  const double qv = bessel_k1_over_k0(xv);
  const T q = lift(qv, qv * qv - qv / xv - 1.0, x);  // K1/K0 at lam a; (K1/K0)' = q^2 - q/x - 1
  StateOf<T> s;
  s.delta_H = g.f + g.df / (lambda * q);  // f'(a) = -w'(a+) = c lam K1/K0
  s.P_H = pi * K * (a * a * s.delta_H - 2.0 * g.M) + 2.0 * pi * G * a * g.df;
  s.S = pi * K * a * a + 2.0 * pi * G * lambda * a * q;
  s.dS_da = 2.0 * pi * K * a * q * q;
  return s;
}

/// Elastic half-space (Galin, Sneddon's form) from the profile's integrals
/// I0 = delta_H / a and I2 = P_H / (2 E* a^2); E* = E/(1 - nu^2).
template <class T>
StateOf<T> half_space_state(const T& a, const T& I0, const T& I2, const T& E_star) {
  StateOf<T> s;
  s.delta_H = a * I0;
  s.P_H = 2.0 * E_star * a * a * I2;
  s.S = 2.0 * E_star * a;
  s.dS_da = 2.0 * E_star;
  return s;
}

}  // namespace layerjkr::detail
