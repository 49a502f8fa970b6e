// Internal: the Maugis-Dugdale half-space equations (Maugis 1992, in the notation of Johnson &
// Greenwood 1997), written once and templated on the scalar: the library solves them on
// double (maugis_dugdale.cpp), the fit differentiates them on ceres::Jet.
//
// Dimensionless: A = a (K/(pi w R^2))^(1/3), Pbar = P/(pi w R),
// Deltabar = delta (K^2/(pi^2 w^2 R))^(1/3), K = 4 E*/3, m = c/a, and the unknown
// s = sqrt(m^2 - 1) (m itself loses all digits of m - 1 as lambda -> infinity):
//
//   (lambda A^2/2) g1(s) + (4 lambda^2 A/3) g2(s) = 1,
//       g1(s) = sqrt(m^2-1) + (m^2-2) atan sqrt(m^2-1) = s + (s^2 - 1) atan s,
//       g2(s) = sqrt(m^2-1) atan sqrt(m^2-1) - m + 1   (atan sqrt(m^2-1) = arccos(1/m)),
//   Pbar     = A^3 - lambda A^2 [s + m^2 atan s],
//   Deltabar = A^2 - (4/3) lambda A s.
//
// Both g1 and g2 increase strictly from g(0) = 0, so the first equation has exactly one root
// s > 0 for A > 0. Every product is grouped as (A s), (A m) so that s up to 1e300 (A -> 0,
// where C = A m stays finite) does not overflow.
#pragma once

#include <cmath>
#include <limits>

#include "core/scalar.hpp"

namespace layerjkr::detail {

/// g1(s) = s + (s^2 - 1) atan s. Below s = 1/2 the two terms cancel to (4/3) s^3, so the
/// series sum_{j>=1} (-1)^(j-1) 4j/(4j^2-1) s^(2j+1) is used there (ratio <= s^2 = 1/4;
/// above it the direct form loses at most a factor 3.3).
template <class T>
T maugis_g1_small(const T& s) {
  const T s2 = s * s;
  T power = s * s2;
  T sum = T(0.0);
  for (int j = 1; j < 40; ++j) {
    const double coefficient = (j % 2 == 1 ? 4.0 : -4.0) * j / (4.0 * j * j - 1.0);
    const T term = coefficient * power;
    sum += term;
    if (std::abs(value_of(term)) <= 1e-18 * std::abs(value_of(sum))) break;
    power *= s2;
  }
  return sum;
}

/// The products the equations need. They are built from (A, A s, A m) rather than from s, so
/// that s up to 1e300 (A -> 0, where C = A m stays finite) does not overflow, and so that a
/// caller differentiating at fixed C (maugis_terms_at_c) does not cancel s against A ds/dA.
template <class T>
struct MaugisTerms {
  T A2g1;      ///< A^2 g1(s)
  T Ag2;       ///< A g2(s)
  T As;        ///< A s = sqrt(c^2 - a^2) in A's units
  T Am;        ///< A m = C, c in A's units
  T atan_s;    ///< atan s = arccos(1/m)
};

template <class T>
MaugisTerms<T> maugis_terms_from(const T& A, const T& As, const T& Am, double s) {
  using std::atan2;
  MaugisTerms<T> t;
  t.As = As;
  t.Am = Am;
  t.atan_s = atan2(As, A);
  if (s < 0.5) {
    const T sj = As / A;
    t.A2g1 = A * A * maugis_g1_small(sj);
  } else {
    t.A2g1 = A * As + (As * As - A * A) * t.atan_s;
  }
  // g2 = s atan s - (m - 1), m - 1 = s^2/(1 + m): at most a factor 2 cancels (s -> 0).
  t.Ag2 = As * t.atan_s - As * As / (A + Am);
  return t;
}

/// The terms at (A > 0, s = sqrt(m^2 - 1)), the unknown the library solves for.
template <class T>
MaugisTerms<T> maugis_terms(const T& A, const T& s) {
  using std::hypot;
  return maugis_terms_from(A, T(A * s), T(A * hypot(T(1.0), s)), value_of(s));
}

/// The same terms at (A > 0, C = A m): for m well above 1 only (C - A loses the digits of
/// m - 1 as m -> 1).
template <class T>
MaugisTerms<T> maugis_terms_at_c(const T& A, const T& C) {
  using std::sqrt;
  const T As = sqrt((C - A) * (C + A));
  return maugis_terms_from(A, As, C, value_of(As) / value_of(A));
}

/// Residual of the first equation, zero at the solution.
template <class T>
T maugis_residual(const T& lambda, const MaugisTerms<T>& t) {
  return 0.5 * lambda * t.A2g1 + (4.0 / 3.0) * lambda * lambda * t.Ag2 - 1.0;
}

/// Pbar = A^3 - lambda [A (A s) + (A m)^2 atan s].
template <class T>
T maugis_force(const T& lambda, const T& A, const MaugisTerms<T>& t) {
  return A * A * A - lambda * (A * t.As + t.Am * t.Am * t.atan_s);
}

/// Deltabar = A^2 - (4/3) lambda A (A s).
template <class T>
T maugis_approach(const T& lambda, const T& A, const MaugisTerms<T>& t) {
  return A * A - (4.0 / 3.0) * lambda * t.As;
}

/// The no-contact limit A -> 0 with C = A m finite (surfaces touching at r = 0, the Dugdale
/// zone over r < c): lambda pi C^2/4 + (4/3) lambda^2 (pi/2 - 1) C = 1, taken in the form
/// without cancellation; Pbar = -lambda pi C^2 / 2, Deltabar = -(4/3) lambda C.
template <class T>
T maugis_zero_contact_C(const T& lambda) {
  using std::sqrt;
  const double pi = 3.141592653589793238462643383279502884;
  const T alpha = lambda * (pi / 4.0);
  const T beta = (4.0 / 3.0) * (pi / 2.0 - 1.0) * lambda * lambda;
  return 2.0 / (beta + sqrt(beta * beta + 4.0 * alpha));
}

}  // namespace layerjkr::detail
