#include "layerjkr/maugis_dugdale.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <boost/math/constants/constants.hpp>
#include <boost/math/tools/roots.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <ceres/jet.h>

#include "adhesion/maugis_equations.hpp"
#include "layerjkr/error.hpp"
#include "models/state_formulas.hpp"

namespace layerjkr {

namespace {

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kLambdaMin = 1e-4;
constexpr double kLambdaMax = 1e4;
// Below this A the A -> 0 limit is exact in double: its corrections are O(A / C) with C > 1.
constexpr double kTinyA = 1e-200;

void require_lambda(const char* function, double lambda) {
  if (!(lambda >= kLambdaMin && lambda <= kLambdaMax))
    throw DomainError(function, "lambda", lambda, "[1e-4, 1e4]");
}

MaugisPoint zero_contact(double lambda) {
  const double C = detail::maugis_zero_contact_C(lambda);
  return {0.0, std::numeric_limits<double>::infinity(), C, -0.5 * kPi * lambda * C * C,
          -(4.0 / 3.0) * lambda * C};
}

// s = sqrt(m^2 - 1) at (lambda, A > 0): the one root of the first equation, increasing in s.
double solve_s(double lambda, double A) {
  const auto f = [&](double s) { return detail::maugis_residual(lambda, detail::maugis_terms(A, s)); };
  // The guess combines the two regimes: s large (A -> 0, A s -> C) and s small (lambda -> inf,
  // where (2/3) lambda^2 A s^2 + (2/3) lambda A^2 s^3 = 1); the bracket grows from it.
  const double s_large = detail::maugis_zero_contact_C(lambda) / A;
  const double s_small = std::min(std::sqrt(1.5 / (lambda * lambda * A)), std::cbrt(1.5 / (lambda * A * A)));
  std::uintmax_t iterations = 300;
  const auto root = boost::math::tools::bracket_and_solve_root(
      f, std::max(s_large, s_small), 2.0, true, boost::math::tools::eps_tolerance<double>(), iterations);
  if (iterations >= 300)
    throw NumericalError("layerjkr::maugis_point: m did not converge at lambda = " +
                         format_double(lambda) + ", A = " + format_double(A));
  return 0.5 * (root.first + root.second);
}

MaugisPoint point_at(double lambda, double A) {
  if (A < kTinyA) {
    MaugisPoint p = zero_contact(lambda);
    if (A > 0.0) {
      p.A = A;
      p.m = p.C / A;
    }
    return p;
  }
  const double s = solve_s(lambda, A);
  const auto t = detail::maugis_terms(A, s);
  return {A, std::hypot(1.0, s), t.Am, detail::maugis_force(lambda, A, t),
          detail::maugis_approach(lambda, A, t)};
}

// d/dA of Pbar (force) or Deltabar along the solution, by the implicit function theorem on the
// same templates (Jet in A and the second unknown). For m > sqrt 2 the second unknown is
// C = A m, not s: at fixed s, d(A s)/dA = s + A ds/dA cancels s against s as A -> 0 (to
// 1/s^2), at fixed C nothing does, which keeps the pull-off radius accurate as lambda -> 0.
double slope(double lambda, double A, bool force) {
  using Jet = ceres::Jet<double, 2>;
  const double s = solve_s(lambda, A);
  const Jet Aj(A, 0);
  const Jet lj(lambda);
  const auto t = s > 1.0 ? detail::maugis_terms_at_c(Aj, Jet(A * std::hypot(1.0, s), 1))
                         : detail::maugis_terms(Aj, Jet(s, 1));
  const Jet F = detail::maugis_residual(lj, t);
  const Jet G = force ? detail::maugis_force(lj, Aj, t) : detail::maugis_approach(lj, Aj, t);
  return G.v[0] - G.v[1] * F.v[0] / F.v[1];
}

// The A > 0 where slope changes sign from - to + (one such root: Pbar and Deltabar fall from
// A = 0, then rise like A^3 and A^2), bracketed from a guess.
double extremum(const char* function, double lambda, bool force, double guess) {
  std::uintmax_t iterations = 300;
  const auto root = boost::math::tools::bracket_and_solve_root(
      [&](double A) { return slope(lambda, A, force); }, guess, 2.0, true,
      boost::math::tools::eps_tolerance<double>(), iterations);
  if (iterations >= 300)
    throw NumericalError(std::string("layerjkr::") + function + ": no minimum found at lambda = " +
                         format_double(lambda));
  return 0.5 * (root.first + root.second);
}

// Length, force and approach scales of the dimensionless variables.
struct Scales {
  double lambda, length, force, approach;
};

Scales scales(const char* function, double R, double E_star, double w, double sigma0) {
  detail::require_positive(function, "R", R);
  detail::require_positive(function, "E_star", E_star);
  detail::require_positive(function, "w", w);
  detail::require_positive(function, "sigma0", sigma0);
  const double K = 4.0 * E_star / 3.0;
  Scales s{maugis_lambda(R, E_star, w, sigma0), std::cbrt(kPi * w * R * R / K), kPi * w * R,
           std::cbrt(kPi * kPi * w * w * R / (K * K))};
  if (!(s.lambda >= kLambdaMin && s.lambda <= kLambdaMax))
    throw DomainError(function, "lambda = maugis_lambda(R, E_star, w, sigma0)", s.lambda, "[1e-4, 1e4]");
  return s;
}

CriticalPoint dimensional(const MaugisPoint& p, const Scales& s) {
  return {p.A * s.length, p.P * s.force, p.Delta * s.approach};
}

}  // namespace

double maugis_lambda(double R, double E_star, double w, double sigma0) {
  detail::require_positive("maugis_lambda", "R", R);
  detail::require_positive("maugis_lambda", "E_star", E_star);
  detail::require_positive("maugis_lambda", "w", w);
  detail::require_positive("maugis_lambda", "sigma0", sigma0);
  const double K = 4.0 * E_star / 3.0;
  return 2.0 * sigma0 * std::cbrt(R / (kPi * w * K * K));
}

double tabor_parameter(double R, double E_star, double w, double z0) {
  detail::require_positive("tabor_parameter", "R", R);
  detail::require_positive("tabor_parameter", "E_star", E_star);
  detail::require_positive("tabor_parameter", "w", w);
  detail::require_positive("tabor_parameter", "z0", z0);
  return std::cbrt(R * w * w / (E_star * E_star * z0 * z0 * z0));
}

double lennard_jones_dugdale_stress(double w, double z0) {
  detail::require_positive("lennard_jones_dugdale_stress", "w", w);
  detail::require_positive("lennard_jones_dugdale_stress", "z0", z0);
  return 16.0 * w / (9.0 * std::sqrt(3.0) * z0);
}

MaugisPoint maugis_point(double lambda, double A) {
  require_lambda("maugis_point", lambda);
  detail::require_non_negative("maugis_point", "A", A);
  return point_at(lambda, A);
}

double maugis_pull_off_force(double lambda) {
  if (!(lambda > 0.0) || !std::isfinite(lambda)) throw DomainError("maugis_pull_off_force", "lambda", lambda, "finite and > 0");
  if (lambda < kLambdaMin) return -2.0 + 16.0 * (0.5 * kPi - 1.0) / (3.0 * std::sqrt(kPi)) * std::pow(lambda, 1.5);
  if (lambda > kLambdaMax) return -1.5 - std::pow(1.5, 5.0 / 3.0) / (12.0 * lambda * lambda);
  return maugis_pull_off(lambda).P;
}

MaugisPoint maugis_pull_off(double lambda) {
  require_lambda("maugis_pull_off", lambda);
  // Small lambda: the minimum of A^3 - 2 - pi lambda A^2; large: JKR's (3/2)^(1/3).
  const double guess = lambda < 0.3 ? 2.0 * kPi * lambda / 3.0 : 1.0;
  return point_at(lambda, extremum("maugis_pull_off", lambda, true, guess));
}

std::optional<MaugisPoint> maugis_fixed_grips(double lambda) {
  require_lambda("maugis_fixed_grips", lambda);
  if (lambda <= kMaugisFixedGripsLambda) return std::nullopt;
  return point_at(lambda, extremum("maugis_fixed_grips", lambda, false, 0.55));
}

AdhesiveState maugis_dugdale_half_space(double R, double E_star, double w, double sigma0, double a) {
  const Scales s = scales("maugis_dugdale_half_space", R, E_star, w, sigma0);
  detail::require_non_negative("maugis_dugdale_half_space", "a", a);
  const MaugisPoint p = point_at(s.lambda, a / s.length);
  AdhesiveState state;
  state.a = a;
  state.c = p.C * s.length;
  state.P = p.P * s.force;
  state.delta = p.Delta * s.approach;
  // The paraboloid's Sneddon integrals: I0 = a/R, I2 = 2a/(3R).
  const auto h = detail::half_space_state(a, a / R, 2.0 * a / (3.0 * R), E_star);
  state.hertz = {a, h.P_H, h.delta_H, h.S, h.dS_da};
  return state;
}

CriticalPoint maugis_dugdale_pull_off(double R, double E_star, double w, double sigma0) {
  const Scales s = scales("maugis_dugdale_pull_off", R, E_star, w, sigma0);
  return dimensional(maugis_pull_off(s.lambda), s);
}

std::optional<CriticalPoint> maugis_dugdale_fixed_grips(double R, double E_star, double w, double sigma0) {
  const Scales s = scales("maugis_dugdale_fixed_grips", R, E_star, w, sigma0);
  const auto p = maugis_fixed_grips(s.lambda);
  if (!p) return std::nullopt;
  return dimensional(*p, s);
}

}  // namespace layerjkr
