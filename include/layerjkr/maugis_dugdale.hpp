// layerjkr: Maugis-Dugdale adhesion of a paraboloid on an elastic half-space, in closed form.
//
// The adhesive stress is a constant tension sigma0 [Pa] over the annulus a < r < c outside
// the contact, acting until the gap reaches h0 = w / sigma0 (Maugis 1992, J. Colloid
// Interface Sci. 150, 243; notation of Johnson & Greenwood 1997, JCIS 192, 326). One
// parameter decides between the limits, Maugis' lambda (maugis_lambda): lambda -> infinity
// is JKR (pull-off -3/2 pi w R), lambda -> 0 is DMT (-2 pi w R).
//
// Dimensionless variables (K = 4 E*/3, E* = E/(1 - nu^2), R the paraboloid's radius):
//   A = a (K/(pi w R^2))^(1/3),  C = c (K/(pi w R^2))^(1/3),  m = c/a,
//   Pbar = P/(pi w R),  Deltabar = delta (K^2/(pi^2 w^2 R))^(1/3),
// and the solution at given (lambda, A):
//   (lambda A^2/2)[sqrt(m^2-1) + (m^2-2) arccos(1/m)]
//       + (4 lambda^2 A/3)[sqrt(m^2-1) arccos(1/m) - m + 1] = 1       (m from this)
//   Pbar     = A^3 - lambda A^2 [sqrt(m^2-1) + m^2 arccos(1/m)]
//   Deltabar = A^2 - (4/3) lambda A sqrt(m^2-1)
// (docs/theory.md, "Maugis-Dugdale on the half-space", has the limits and the numerics.)
//
// Valid inputs: lambda in [1e-4, 1e4], A >= 0 finite; anything else throws DomainError
// naming the parameter, its value and this range.
// Accuracy (tests/adhesion/test_maugis_half_space.cpp, against an independent 50-digit
// mpmath solution, tools/maugis_reference.py, 51 values of lambda from 1e-4 to 1e4): a point
// solves the equation to rounding (m by TOMS 748 to full precision); the pull-off Pbar to
// 1e-15 and its A, m, C, Deltabar to 1e-11 relative (7e-12 at lambda = 1e-4, 4e-13 from 0.01
// up); the fixed-grips point to 4e-13.
#pragma once

#include <optional>

#include "layerjkr/contact.hpp"
#include "layerjkr/jkr.hpp"

namespace layerjkr {

/// Maugis' transition parameter lambda = 2 sigma0 (R / (pi w K^2))^(1/3), K = 4 E*/3.
/// R [m], E_star [Pa], w [J/m^2], sigma0 [Pa], all finite and > 0.
double maugis_lambda(double R, double E_star, double w, double sigma0);

/// Tabor's parameter mu = (R w^2 / (E*^2 z0^3))^(1/3); z0 [m] the equilibrium separation.
double tabor_parameter(double R, double E_star, double w, double z0);

/// The Dugdale stress matched to the Lennard-Jones law's maximum stress,
/// sigma0 = 16 w / (9 sqrt(3) z0) [Pa] (Johnson & Greenwood 1997), so that
/// lambda = (32 / (9 sqrt 3)) (3/4)^(2/3) pi^(-1/3) mu = 1.1570 mu (1.15702371...).
double lennard_jones_dugdale_stress(double w, double z0);

/// One dimensionless Maugis-Dugdale state.
struct MaugisPoint {
  double A = 0.0;      ///< contact radius a (K/(pi w R^2))^(1/3)
  double m = 0.0;      ///< c/a > 1 (+infinity at A = 0)
  double C = 0.0;      ///< adhesive-zone radius c in A's units, = m A (finite at A = 0)
  double P = 0.0;      ///< Pbar = P/(pi w R)
  double Delta = 0.0;  ///< Deltabar = delta (K^2/(pi^2 w^2 R))^(1/3)
};

/// The state at contact radius A >= 0 for lambda in [1e-4, 1e4]. A = 0 is the limit A -> 0
/// with C finite: the surfaces touch at r = 0 and the Dugdale zone covers r < C, with
/// lambda pi C^2/4 + (4/3) lambda^2 (pi/2 - 1) C = 1, Pbar = -lambda pi C^2/2,
/// Deltabar = -(4/3) lambda C (m = +infinity).
MaugisPoint maugis_point(double lambda, double A);

/// Pull-off under load control: the minimum of Pbar over A >= 0. It always lies at A > 0:
/// near A = 0, Pbar = Pbar(0) - pi lambda A^2 + ..., so Pbar falls from the no-contact state
/// (the minimum sits at A ~ 2 pi lambda/3 for small lambda, at A -> (3/2)^(1/3) for large).
/// Limits: Pbar = -2 + (16 (pi/2 - 1) / (3 sqrt(pi))) lambda^(3/2) + ... as lambda -> 0,
///         Pbar = -3/2 - (3/2)^(5/3) / (12 lambda^2) + ... as lambda -> infinity.
MaugisPoint maugis_pull_off(double lambda);

/// The pull-off force Pbar of maugis_pull_off for any lambda > 0: beyond [1e-4, 1e4] the two
/// limits above (their next terms are below 1e-9 there). Throws DomainError for lambda <= 0.
double maugis_pull_off_force(double lambda);

/// The instability under fixed grips: the minimum of Deltabar(A) at A > 0. It exists only for
/// lambda > 0.93794745721071221 (below, Deltabar rises from A = 0 and nullopt is returned);
/// it tends to JKR's A = 6^(-1/3), Pbar = -5/6 as lambda -> infinity.
std::optional<MaugisPoint> maugis_fixed_grips(double lambda);

/// The fixed-grips existence threshold of maugis_fixed_grips (by tools/maugis_reference.py:
/// where d^2 Deltabar/dA^2 at A = 0 changes sign).
inline constexpr double kMaugisFixedGripsLambda = 0.93794745721071221;

/// The dimensional state of a paraboloid of radius R [m] on a half-space of plane-strain
/// modulus E_star [Pa] with work of adhesion w [J/m^2] and Dugdale stress sigma0 [Pa], at
/// contact radius a >= 0 [m]: a, c [m], P [N] (negative = tensile), delta [m]; hertz is the
/// Hertz state at the same a. maugis_lambda(R, E_star, w, sigma0) must be in [1e-4, 1e4].
AdhesiveState maugis_dugdale_half_space(double R, double E_star, double w, double sigma0, double a);

/// The load-control pull-off in SI units (maugis_pull_off scaled back).
CriticalPoint maugis_dugdale_pull_off(double R, double E_star, double w, double sigma0);

/// The fixed-grips instability in SI units, where one exists (maugis_fixed_grips).
std::optional<CriticalPoint> maugis_dugdale_fixed_grips(double R, double E_star, double w, double sigma0);

}  // namespace layerjkr
