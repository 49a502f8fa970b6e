// Internal: a relaxation function psi(t) = E(t)/E in the form the hereditary integrals need -
// a sum of decaying exponentials for the history, and psi's exact integral for the newest piece
// (hereditary.hpp). Templated on the scalar so that ceres::Jet carries the fit's derivatives in
// the law's parameters.
//
// Prony laws (the standard linear solid among them) are sums of exponentials: exact.
// The power law psi = (t/t0)^-beta is not; from t^-beta = (1/Gamma(beta)) int exp(beta x - e^x t) dx
// the trapezoidal rule on the lattice x_k = x_first + k h gives
//   t^-beta ~ (h / Gamma(beta)) sum_k e^(beta x_k) exp(-e^(x_k) t),
// whose error is ~exp(-pi^2/h) relative for every t (the integrand is analytic in |Im x| < pi/2).
// Nodes with e^x t_lo > kUpperRate contribute below 1e-19 and are left out; nodes below x_first =
// log(kTailRate / t_hi) are lumped into one term with their summed weight and their mean rate
// (its error is second order in e^x_first t <= 1e-4). Measured: below 4e-10 relative for beta in
// [0.001, 0.99] over t in [t_lo, t_hi] with h = 0.4 (tests/time/test_hereditary.cpp); the
// lattice has 5.8 nodes per decade of t_hi / t_lo, plus 35.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/gamma.hpp>

#include "core/scalar.hpp"
#include "layerjkr/viscoelastic.hpp"

namespace layerjkr::detail {

/// The sum-of-exponentials lattice of the power law (see above).
inline constexpr double kPowerLawStep = 0.4;    ///< h
inline constexpr double kPowerLawUpperRate = 45.0;  ///< e^x_last t_lo
inline constexpr double kPowerLawTailRate = 1e-4;   ///< e^x_first t_hi
/// The largest relative error of the power law's sum of exponentials over [t_lo, t_hi], measured.
inline constexpr double kPowerLawKernelError = 4e-10;

/// x / expm1(x), 1 at x = 0, without cancellation.
template <class T>
T x_over_expm1(const T& x) {
  using std::expm1;
  if (std::abs(value_of(x)) < 1e-8) return T(1.0) - 0.5 * x;
  return x / expm1(x);
}

/// (1 - e^-x) / x, 1 at x = 0, without cancellation.
template <class T>
T one_minus_exp_over(const T& x) {
  using std::expm1;
  if (std::abs(value_of(x)) < 1e-8) return T(1.0) - 0.5 * x;
  return -expm1(-x) / x;
}

/// 1/Gamma(1 + b) for b in [0, 1), on double or Jet.
template <class T>
T reciprocal_gamma_1p(const T& b) {
  const double v = value_of(b), r = 1.0 / boost::math::tgamma(1.0 + v);
  return lift(r, -r * boost::math::digamma(1.0 + v), b);
}

template <class T>
T fractional_integral(const T& beta, const T& tau, const T& plateau, const T& lo, const T& hi);

template <class T>
struct RelaxationKernel {
  /// psi(t) ~ sum_j c[j] exp(-u[j] t) for t >= t_lo (exact for Prony laws); u >= 0.
  std::vector<T> c, u;
  /// The power law psi = p + (1 - p)(t/t0)^-beta (p = plateau, 0 for the plain law), for the
  /// exact integrals; else a Prony law.
  bool power = false;
  /// The fractional standard linear solid p + (1 - p) E_beta(-(t/tau)^beta) (fractional_kernel).
  bool fractional = false;
  T beta{}, plateau{}, tau{};
  double t0 = 1.0;

  /// The same kernel on double (the radius search of hereditary.hpp runs on values).
  RelaxationKernel<double> values() const {
    RelaxationKernel<double> k;
    for (const T& x : c) k.c.push_back(value_of(x));
    for (const T& x : u) k.u.push_back(value_of(x));
    k.power = power;
    k.fractional = fractional;
    k.beta = value_of(beta);
    k.plateau = value_of(plateau);
    k.tau = value_of(tau);
    k.t0 = t0;
    return k;
  }

  /// int_lo^hi psi(r) dr for 0 <= lo <= hi: exact for Prony and power laws (not the sum's), to
  /// 1e-10 relative for the fractional law (fractional_integral).
  T integral(const T& lo, const T& hi) const {
    using std::exp;
    using std::expm1;
    using std::log;
    using std::log1p;
    using std::pow;
    if (fractional) return fractional_integral(beta, tau, plateau, lo, hi);
    if (power) {
      // t0^beta (hi^e - lo^e) / e, e = 1 - beta, with hi^e - lo^e = lo^e expm1(e log1p((hi-lo)/lo)).
      const T e = T(1.0) - beta;
      const T scale = (T(1.0) - plateau) * pow(T(t0), beta) / e;
      if (value_of(lo) <= 0.0) return plateau * hi + scale * pow(hi, e);
      return plateau * (hi - lo) + scale * pow(lo, e) * expm1(e * log1p((hi - lo) / lo));
    }
    T sum(0.0);
    for (std::size_t j = 0; j < c.size(); ++j) {
      const T width = hi - lo;
      if (is_constant_zero(u[j]))
        sum += c[j] * width;
      else
        sum += c[j] * exp(-u[j] * lo) * width * one_minus_exp_over(u[j] * width);
    }
    return sum;
  }
  /// psi(r) for r > 0: exact for Prony and power laws; the fractional law's sum for r in [t_lo, t_hi].
  T value(const T& r) const {
    using std::exp;
    using std::pow;
    if (power) return plateau + (T(1.0) - plateau) * pow(r / t0, -beta);
    T sum(0.0);
    for (std::size_t j = 0; j < c.size(); ++j) sum += c[j] * exp(-u[j] * r);
    return sum;
  }
};

/// A Prony law psi = c_inf + sum_i g_i exp(-t/tau_i): one term per time, and the constant.
template <class T>
RelaxationKernel<T> prony_kernel(const T& c_inf, const std::vector<T>& g, const std::vector<T>& tau) {
  RelaxationKernel<T> k;
  k.c.push_back(c_inf);
  k.u.push_back(T(0.0));
  for (std::size_t i = 0; i < g.size(); ++i) {
    k.c.push_back(g[i]);
    k.u.push_back(T(1.0) / tau[i]);
  }
  return k;
}

/// The power law p + (1 - p)(t/t0)^-beta as a sum of exponentials accurate over [t_lo, t_hi] (0 <
/// t_lo <= t_hi, beta in [0, 1), the plateau p in [0, 1)): the plateau one constant term, the power
/// law's lattice scaled by 1 - p. The lattice depends only on t_lo and t_hi, so its weights are
/// smooth in beta.
template <class T>
RelaxationKernel<T> power_law_kernel(const T& beta, double t0, double t_lo, double t_hi, const T& plateau = T(0.0)) {
  using std::exp;
  using std::expm1;
  using std::pow;
  RelaxationKernel<T> k;
  k.power = true;
  k.beta = beta;
  k.plateau = plateau;
  k.t0 = t0;
  const double h = kPowerLawStep;
  const double x_first = std::log(kPowerLawTailRate / t_hi), x_last = std::log(kPowerLawUpperRate / t_lo);
  const T scale = (T(1.0) - plateau) * pow(T(t0), beta);
  const T rg = reciprocal_gamma_1p(beta);  // h / Gamma(beta) = h beta / Gamma(1 + beta): finite at beta = 0
  // The lumped tail, nodes x_first - m h for m >= 1: their summed weight h e^(beta x_first) /
  // (Gamma(beta) expm1(beta h)) and mean rate e^x_first expm1(beta h) / expm1((1 + beta) h). At
  // beta = 0 it is the whole law, psi = 1, and every node's weight is 0.
  k.c.push_back(scale * exp(beta * x_first) * x_over_expm1(beta * h) * rg);
  k.u.push_back(std::exp(x_first) * expm1(beta * h) / expm1((T(1.0) + beta) * h));
  const int nodes = static_cast<int>(std::floor((x_last - x_first) / h + 0.5)) + 1;
  for (int m = 0; m < nodes; ++m) {
    const double x = x_first + m * h;  // not accumulated: no drift over the nodes
    k.c.push_back(scale * h * beta * rg * exp(beta * x));
    k.u.push_back(T(std::exp(x)));
  }
  if (!is_constant_zero(plateau)) {
    k.c.push_back(plateau);
    k.u.push_back(T(0.0));
  }
  return k;
}

/// The fractional standard linear solid (a spring in parallel with a spring and a springpot in
/// series; the fractional Maxwell model at p = 0): psi = p + (1 - p) E_beta(-(t/tau)^beta), with
/// E_beta the Mittag-Leffler function, is completely monotone with the relaxation spectrum
///   E_beta(-(t/tau)^beta) = int w(x) exp(-e^x t/tau) dx,  w(x) = sin(beta pi) / (2 pi (cosh(beta x)
///   + cos(beta pi))) = sin(beta pi) / (4 pi (sinh^2(beta x / 2) + cos^2(beta pi / 2))),
/// (the Laplace transform of E_beta(-t^beta) is s^(beta-1)/(s^beta + 1); docs/theory.md s.8b). w is
/// even, integrates to 1, and is analytic in |Im x| < pi (1 - beta)/beta: the trapezoidal rule in x
/// with the step h = min(0.4, 0.8 (1 - beta)/beta) errs by ~exp(-2 pi^2/0.8) = 2e-11, as the power
/// law's with h = 0.4. Below x_lo = min(ln(1e-5 tau/t_hi), ln(0.8)/beta) the lattice's nodes are summed
/// in closed form from w(x) = (1/pi) sum_k (-1)^k sin((k+1) beta pi) e^((k+1) beta x) (x < 0): their
/// weight and mean rate, lumped into one term (second order in e^x_lo t_hi/tau <= 1e-5).
namespace fractional {

inline constexpr double kLowRate = 1e-5;   ///< e^x_lo t_far / tau: below, the lattice is summed as a series
inline constexpr double kSeriesRatio = 0.8;  ///< e^(beta x_lo) at most: the series' ratio
inline constexpr double kUpperRate = 45.0;   ///< e^x t_lo / tau above which a history term is < 3e-20
inline constexpr double kBetaMin = 0.01, kBetaMax = 0.95;  ///< the exponents the law accepts (validate)
inline constexpr double kPi = boost::math::constants::pi<double>();

inline double step(double beta) { return std::min(kPowerLawStep, 2.0 * kPowerLawStep * (1.0 - beta) / beta); }
inline double lowest_node(double beta, double tau, double t_far) {
  return std::min(std::log(kLowRate * tau / t_far), std::log(kSeriesRatio) / beta);
}

/// w(x) h, the weight of the node at x.
template <class T>
T weight(const T& beta, double x, double h) {
  using std::cos;
  using std::sin;
  using std::sinh;
  const T sh = sinh(0.5 * beta * x), co = cos(0.5 * kPi * beta);
  return h * sin(kPi * beta) / (4.0 * kPi * (sh * sh + co * co));
}

/// The nodes below x_lo (x_lo - m h, m >= 1): their summed weight S0 and sum of weight times
/// e^x, S1, from the series of w (e^(beta x_lo) <= 0.8: 150 terms reach 1e-14).
template <class T>
void tail_sums(const T& beta, double x_lo, double h, T* S0, T* S1) {
  using std::exp;
  using std::expm1;
  using std::sin;
  const T y0 = exp(beta * x_lo);
  const double y0v = value_of(y0);
  const int terms = y0v <= 0.0 ? 1 : std::min(400, static_cast<int>(std::ceil(std::log(1e-15) / std::log(y0v))) + 1);
  *S0 = T(0.0);
  *S1 = T(0.0);
  T y = y0;
  for (int k = 0; k < terms; ++k) {
    const T a = ((k % 2) ? -1.0 : 1.0) * sin(kPi * (k + 1.0) * beta) * y;
    *S0 += a / expm1((k + 1.0) * beta * h);
    *S1 += a / expm1(((k + 1.0) * beta + 1.0) * h);
    y *= y0;
  }
  *S0 *= h / kPi;
  *S1 *= h / kPi * std::exp(x_lo);
}

}  // namespace fractional

/// The fractional law's sum of exponentials accurate over [t_lo, t_hi] (see above): the lumped
/// low-rate tail, the lattice up to e^x t_lo/tau = 45, and the plateau one constant term.
template <class T>
RelaxationKernel<T> fractional_kernel(const T& beta, const T& tau, double t_lo, double t_hi, const T& plateau = T(0.0)) {
  RelaxationKernel<T> k;
  k.fractional = true;
  k.beta = beta;
  k.tau = tau;
  k.plateau = plateau;
  const double b = value_of(beta), tv = value_of(tau), h = fractional::step(b);
  const double x_lo = fractional::lowest_node(b, tv, t_hi), x_hi = std::log(fractional::kUpperRate * tv / t_lo);
  const T scale = T(1.0) - plateau;
  T S0, S1;
  fractional::tail_sums(beta, x_lo, h, &S0, &S1);
  k.c.push_back(scale * S0);
  k.u.push_back(S1 / (S0 * tau));
  for (int m = 0; x_lo + m * h <= x_hi + 0.5 * h; ++m) {
    const double x = x_lo + m * h;
    k.c.push_back(scale * fractional::weight(beta, x, h));
    k.u.push_back(std::exp(x) / tau);
  }
  if (!is_constant_zero(plateau)) {
    k.c.push_back(plateau);
    k.u.push_back(T(0.0));
  }
  return k;
}

/// int_lo^hi psi(r) dr of the fractional law (0 <= lo <= hi [s]): p (hi - lo) plus (1 - p) times the
/// spectrum's int w(x) tau e^-x (exp(-e^x lo/tau) - exp(-e^x hi/tau)) dx on the same lattice, from
/// x_lo (below: the series' sums, to second order) to where the integrand has fallen below 1e-12 of
/// the integral. 1e-10 relative.
template <class T>
T fractional_integral(const T& beta, const T& tau, const T& plateau, const T& lo, const T& hi) {
  using std::exp;
  using std::expm1;
  const T width = hi - lo;
  if (!(value_of(width) > 0.0)) return T(0.0);
  const double b = value_of(beta), tv = value_of(tau), h = fractional::step(b);
  const double x_lo = fractional::lowest_node(b, tv, value_of(hi));
  // Above x_top every term is below 1e-12 of the integral: the unsettled part decays as
  // e^-((1 + beta) x), and a positive lo cuts it off double-exponentially.
  double x_top = (28.0 + std::max(0.0, std::log(tv / value_of(width)))) / (1.0 + b) + 1.0;
  if (value_of(lo) > 0.0) x_top = std::min(x_top, std::log(fractional::kUpperRate * tv / value_of(lo)));
  T S0, S1;
  fractional::tail_sums(beta, x_lo, h, &S0, &S1);
  T sum = S0 * width - S1 * (hi * hi - lo * lo) / (2.0 * tau);
  for (int m = 0; x_lo + m * h <= x_top; ++m) {
    const double x = x_lo + m * h;
    const T rate = std::exp(x) / tau;
    sum += fractional::weight(beta, x, h) * exp(-rate * lo) * (-expm1(-rate * width)) / rate;
  }
  return plateau * width + (T(1.0) - plateau) * sum;
}

/// The kernel of a validated law for times in [t_lo, t_hi] (0 < t_lo <= t_hi) [s]: Prony laws exactly,
/// the power law as the sum above, the elastic law as psi = 1 (hereditary.cpp).
RelaxationKernel<double> kernel_of(const RelaxationLaw& law, double t_lo, double t_hi);

/// The smallest step and the whole span of increasing times t [s]: the range a power law's sum of
/// exponentials must cover in a hereditary response over them (hereditary.cpp).
void time_scales(const std::vector<double>& t, double* t_lo, double* t_hi);

}  // namespace layerjkr::detail
