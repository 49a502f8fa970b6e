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
// [0.001, 0.99] over t in [t_lo, t_hi] with h = 0.4 (tests/viscoelastic/test_hereditary.cpp); the
// lattice has 5.8 nodes per decade of t_hi / t_lo, plus 35.
#pragma once

#include <cmath>
#include <vector>

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
struct RelaxationKernel {
  /// psi(t) ~ sum_j c[j] exp(-u[j] t) for t >= t_lo (exact for Prony laws); u >= 0.
  std::vector<T> c, u;
  /// The power law psi = p + (1 - p)(t/t0)^-beta (p = plateau, 0 for the plain law), for the
  /// exact integrals; else a Prony law.
  bool power = false;
  T beta{}, plateau{};
  double t0 = 1.0;

  /// int_lo^hi psi(r) dr for 0 <= lo <= hi, exact (not the sum's).
  T integral(const T& lo, const T& hi) const {
    using std::exp;
    using std::expm1;
    using std::log;
    using std::log1p;
    using std::pow;
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
  /// psi(r) for r > 0, exact.
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

/// The kernel of a validated law for times in [t_lo, t_hi] (0 < t_lo <= t_hi) [s]: Prony laws exactly,
/// the power law as the sum above, the elastic law as psi = 1 (hereditary.cpp).
RelaxationKernel<double> kernel_of(const RelaxationLaw& law, double t_lo, double t_hi);

/// The smallest step and the whole span of increasing times t [s]: the range a power law's sum of
/// exponentials must cover in a hereditary response over them (hereditary.cpp).
void time_scales(const std::vector<double>& t, double* t_lo, double* t_hi);

}  // namespace layerjkr::detail
