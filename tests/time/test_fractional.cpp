// The fractional standard linear solid, psi = p + (1 - p) E_beta(-(t/tau)^beta), against
// independent evaluations of the Mittag-Leffler function written differently from the library's
// relaxation spectrum: the closed form E_1/2(-x) = exp(x^2) erfc(x), Boost's adaptive quadrature of
// the spectrum in another variable, the power series
// sum (-z)^k / Gamma(beta k + g) for small z, the asymptotic series for large z; the hereditary
// (Lee-Radok) force of a paraboloid pressed at constant speed against t^1.5 E_beta,5/2; the exact
// integral of psi against t E_beta,2; the Jet derivatives against central differences; the limits.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <ceres/jet.h>

#include "layerjkr/error.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "time/relaxation_kernel.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

double rel_err(double a, double b) { return std::abs(a - b) / std::abs(b); }

// E_{beta,g}(-z) by its power series; for z <= 3 the alternating terms stay below 1e2, so the
// sum keeps 1e-13 of its value.
double mittag_leffler_series(double beta, double g, double z) {
  double sum = 0.0, zk = 1.0;
  for (int k = 0; k < 400; ++k) {
    const double term = zk / boost::math::tgamma(beta * k + g);
    sum += (k % 2 ? -term : term);
    if (std::abs(term) < 1e-18 && k > 5) break;
    zk *= z;
  }
  return sum;
}

// E_beta(-z) as the Laplace transform of its spectrum in the variable s = (r tau)^beta, where the
// spectrum is smooth: (sin(beta pi) / (beta pi)) int_0^inf exp(-(s z)^(1/beta)) / (s^2 + 2 s cos(beta pi)
// + 1) ds; the exponential falls like a step at s = 1/z for small beta, so the two sides are
// integrated apart (tanh-sinh below, exp-sinh above). Boost's quadrature, not the library's lattice.
double mittag_leffler_quadrature(double beta, double z) {
  const double pi = boost::math::constants::pi<double>(), c = std::cos(beta * pi);
  const auto f = [&](double s) { return std::exp(-std::pow(s * z, 1.0 / beta)) / (s * s + 2.0 * s * c + 1.0); };
  boost::math::quadrature::tanh_sinh<double> below;
  boost::math::quadrature::exp_sinh<double> above;
  const double edge = 1.0 / z;
  const double sum = below.integrate(f, 0.0, edge, 1e-14) + above.integrate([&](double u) { return f(edge + u); }, 1e-14);
  return std::sin(beta * pi) / (beta * pi) * sum;
}

// E_beta(-z) ~ sum_{k=1..K} (-1)^(k+1) z^-k / Gamma(1 - beta k) for large z (1/Gamma at its poles is 0).
double mittag_leffler_asymptotic(double beta, double z) {
  double sum = 0.0;
  for (int k = 1; k <= 8; ++k) {
    const double x = 1.0 - beta * k;
    if (std::abs(x - std::round(x)) < 1e-12 && x <= 0.0) continue;
    sum += (k % 2 ? 1.0 : -1.0) * std::pow(z, -k) / boost::math::tgamma(x);
  }
  return sum;
}

}  // namespace

TEST_CASE("fractional law: psi against exp(x^2) erfc(x) at beta = 1/2", "[viscoelastic][fractional]") {
  const double tau = 0.3;
  const RelaxationLaw law = RelaxationLaw::fractional_maxwell(0.5, tau);
  for (double theta : {1e-6, 1e-4, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 100.0}) {
    const double x = std::sqrt(theta);
    // exp(x^2) erfc(x), written for large x from the scaled complementary error function's series.
    const double exact = x < 20.0 ? std::exp(x * x) * boost::math::erfc(x)
                                  : 1.0 / (x * std::sqrt(boost::math::constants::pi<double>())) * (1.0 - 0.5 / (x * x) + 0.75 / std::pow(x, 4));
    INFO("t/tau = " << theta);
    CHECK(rel_err(law.relative_modulus(theta * tau), exact) < 1e-9);
  }
}

TEST_CASE("fractional law: psi against the Mittag-Leffler series and asymptotics", "[viscoelastic][fractional]") {
  for (double beta : {0.01, 0.05, 0.2, 0.45, 0.7, 0.9, 0.95})
    for (double tau : {1e-3, 2.0}) {
      const RelaxationLaw law = RelaxationLaw::fractional_maxwell(beta, tau);
      for (double z : {1e-3, 0.1, 0.5, 1.0, 2.0, 5.0, 20.0}) {
        const double t = tau * std::pow(z, 1.0 / beta);
        if (!(t > 1e-300 && t < 1e300)) continue;
        INFO("beta " << beta << ", tau " << tau << ", z = (t/tau)^beta = " << z);
        const double psi = law.relative_modulus(t);
        CHECK(rel_err(psi, mittag_leffler_quadrature(beta, z)) < 2e-10);
        // The series converges where its terms stay small: z <= 1 beyond beta = 0.2.
        if (z <= 0.5 || (z <= 1.0 && beta >= 0.2)) CHECK(rel_err(psi, mittag_leffler_series(beta, 1.0, z)) < 2e-10);
      }
      for (double z : {200.0, 1e3}) {
        const double t = tau * std::pow(z, 1.0 / beta);
        if (!(t < 1e300)) continue;
        INFO("beta " << beta << ", large z = " << z);
        CHECK(rel_err(law.relative_modulus(t), mittag_leffler_asymptotic(beta, z)) < 1e-9);
      }
    }
  // The plateau: E_inf/E + (1 - E_inf/E) E_beta.
  const RelaxationLaw sls = RelaxationLaw::fractional_sls(0.3, 0.5, 0.25);
  CHECK(rel_err(sls.relative_modulus(0.2), 0.25 + 0.75 * mittag_leffler_series(0.3, 1.0, std::pow(0.4, 0.3))) < 2e-10);
  CHECK(sls.describe() == "fractional_sls(beta = 0.3, tau = 0.5 s, E_inf/E = 0.25)");
  CHECK(RelaxationLaw::fractional_maxwell(0.3, 0.5).describe() == "fractional_maxwell(beta = 0.3, tau = 0.5 s)");
}

TEST_CASE("fractional law: the exact integral of psi against t E_beta,2(-(t/tau)^beta)", "[viscoelastic][fractional]") {
  for (double beta : {0.05, 0.3, 0.6, 0.9})
    for (double p : {0.0, 0.4}) {
      const double tau = 0.05;
      const auto integral_to = [&](double t) {
        return p * t + (1.0 - p) * t * mittag_leffler_series(beta, 2.0, std::pow(t / tau, beta));
      };
      for (double lo : {0.0, 1e-5, 0.01}) {
        const double hi = lo + 0.004;  // z <= (0.014/0.05)^beta < 1
        const double got = detail::fractional_integral<double>(beta, tau, p, lo, hi);
        INFO("beta " << beta << ", E_inf/E " << p << ", [" << lo << ", " << hi << "] s");
        CHECK(rel_err(got, integral_to(hi) - integral_to(lo)) < 1e-10);
      }
      // A piece far longer than tau: the integral is dominated by the long-time tail.
      const double long_hi = 1e3 * tau;
      const double by_kernel = detail::fractional_integral<double>(beta, tau, p, 0.0, long_hi);
      const double by_split = detail::fractional_integral<double>(beta, tau, p, 0.0, 0.1 * tau) +
                              detail::fractional_integral<double>(beta, tau, p, 0.1 * tau, long_hi);
      CHECK(rel_err(by_kernel, by_split) < 1e-10);
    }
}

TEST_CASE("fractional law: Lee-Radok force of a paraboloid at constant speed against t^1.5 E_beta,5/2", "[viscoelastic][fractional]") {
  // P_H = C t^1.5 gives P(t) = C (3/2) int psi(t - s) s^1/2 ds = C t^1.5 Gamma(5/2) E_beta,5/2(-(t/tau)^beta).
  for (double beta : {0.1, 0.5, 0.85}) {
    const double tau = 0.2, C = 3e-6, t_end = 0.6;  // (t/tau)^beta <= 3
    const RelaxationLaw law = RelaxationLaw::fractional_maxwell(beta, tau);
    std::vector<double> t, PH;
    const int n = 4000;
    for (int i = 1; i <= n; ++i) {
      t.push_back(t_end * i / n);
      PH.push_back(C * std::pow(t.back(), 1.5));
    }
    const std::vector<double> P = lee_radok_loading(t, PH, law);
    double worst = 0.0;
    for (int i = 99; i < n; i += 100) {
      const double exact = PH[i] * boost::math::tgamma(2.5) * mittag_leffler_series(beta, 2.5, std::pow(t[i] / tau, beta));
      worst = std::max(worst, rel_err(P[i], exact));
    }
    INFO("beta " << beta << ": worst relative error " << worst);
    CHECK(worst < 5e-6);  // measured 1.3e-6 to 2.6e-6: linear interpolation of t^1.5 over 4 000 pieces
  }
}

TEST_CASE("fractional law: the kernel's Jet derivatives in beta, tau and the plateau match central differences",
          "[viscoelastic][fractional]") {
  using J = ceres::Jet<double, 3>;
  const double beta = 0.35, tau = 0.4, p = 0.2, t_lo = 1e-3, t_hi = 20.0;
  const auto k = detail::fractional_kernel<J>(J(beta, 0), J(tau, 1), t_lo, t_hi, J(p, 2));
  for (double t : {2e-3, 0.05, 0.4, 3.0, 19.0}) {
    const J psi = k.value(J(t));
    const J area = k.integral(J(0.0), J(t));
    const double eps = 1e-6;
    const auto psi_at = [&](double b, double ta, double pl) {
      return detail::fractional_kernel<double>(b, ta, t_lo, t_hi, pl).value(t);
    };
    const auto area_at = [&](double b, double ta, double pl) { return detail::fractional_integral<double>(b, ta, pl, 0.0, t); };
    INFO("t = " << t);
    CHECK(psi.v[0] == Approx((psi_at(beta + eps, tau, p) - psi_at(beta - eps, tau, p)) / (2 * eps)).epsilon(1e-6));
    CHECK(psi.v[1] == Approx((psi_at(beta, tau + eps, p) - psi_at(beta, tau - eps, p)) / (2 * eps)).epsilon(1e-6));
    CHECK(psi.v[2] == Approx((psi_at(beta, tau, p + eps) - psi_at(beta, tau, p - eps)) / (2 * eps)).epsilon(1e-6));
    CHECK(area.v[0] == Approx((area_at(beta + eps, tau, p) - area_at(beta - eps, tau, p)) / (2 * eps)).epsilon(1e-6));
    CHECK(area.v[1] == Approx((area_at(beta, tau + eps, p) - area_at(beta, tau - eps, p)) / (2 * eps)).epsilon(1e-6));
  }
}

TEST_CASE("fractional law: limits and refusals", "[viscoelastic][fractional]") {
  // Early: psi ~ 1 - (t/tau)^beta / Gamma(1 + beta); near beta = 0.95 the law approaches the SLS's exp(-t/tau).
  const RelaxationLaw early = RelaxationLaw::fractional_maxwell(0.4, 1.0);
  CHECK(1.0 - early.relative_modulus(1e-12) == Approx(std::pow(1e-12, 0.4) / boost::math::tgamma(1.4)).epsilon(1e-4));
  const RelaxationLaw near_one = RelaxationLaw::fractional_maxwell(0.95, 1.0);
  CHECK(near_one.relative_modulus(1.0) == Approx(std::exp(-1.0)).epsilon(0.05));
  CHECK_THROWS_AS(RelaxationLaw::fractional_maxwell(0.99, 1.0), DomainError);
  CHECK_THROWS_AS(RelaxationLaw::fractional_maxwell(0.0, 1.0), DomainError);
  CHECK_THROWS_AS(RelaxationLaw::fractional_maxwell(0.3, 0.0), DomainError);
  CHECK_THROWS_AS(RelaxationLaw::fractional_sls(0.3, 1.0, 1.0), DomainError);
  CHECK_THROWS_WITH(RelaxationLaw::fractional_maxwell(0.99, 1.0), Catch::Contains("[0.01, 0.95]"));
}
