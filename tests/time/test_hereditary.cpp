// The hereditary response (Lee-Radok loading, Ting's unloading) against closed forms and a second
// method: Efremov et al. 2017's power-law paraboloid on a half-space (loading and unloading with
// t1 from (t - t1)^(1-b) = (1 + v_r/v)(t - t_m)^(1-b)); a standard linear solid by Gauss-Kronrod
// quadrature of the hereditary integrals and a bracketed root for t1 (not the library's
// recursions); the power law's sum of exponentials against t^-beta and its beta-derivative; the
// elastic limits; a noisy history; bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/beta.hpp>
#include <boost/math/tools/roots.hpp>
#include <ceres/jet.h>

#include "layerjkr/error.hpp"
#include "layerjkr/viscoelastic.hpp"
#include "time/relaxation_kernel.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

// A paraboloid R on a half-space of instantaneous E* (at t0 for a power law): P_H = (4/3) E* sqrt(R) d^1.5.
constexpr double kEstar = 1000.0 / 0.75, kR = 5e-6;  // Pa, m
double hertz(double d) { return d > 0.0 ? 4.0 / 3.0 * kEstar * std::sqrt(kR) * std::pow(d, 1.5) : 0.0; }

double rel_err(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Indentation at speed v from contact at t = 0 to t_m, then back at v_r: samples every dt from t = 0.
struct Triangle {
  double v, v_r, t_m;
  double delta(double t) const { return t <= t_m ? v * t : v * t_m - v_r * (t - t_m); }
};

struct History {
  std::vector<double> t, delta;
};
History sample(const Triangle& tri, double t_end, int n) {
  History h;
  for (int i = 0; i <= n; ++i) {
    h.t.push_back(t_end * i / n);
    h.delta.push_back(tri.delta(h.t.back()));
  }
  return h;
}

}  // namespace

TEST_CASE("the power law's sum of exponentials: within 4e-10 of t^-beta, and its beta-derivative", "[viscoelastic]") {
  for (double decades : {2.0, 4.0, 6.0})
    for (double beta : {0.0, 0.001, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99}) {
      const double t_lo = 2e-4, t_hi = t_lo * std::pow(10.0, decades), t0 = 0.7;
      const auto k = detail::power_law_kernel<double>(beta, t0, t_lo, t_hi);
      double worst = 0.0;
      for (int i = 0; i <= 500; ++i) {
        const double t = t_lo * std::pow(t_hi / t_lo, i / 500.0);
        double sum = 0.0;
        for (std::size_t j = 0; j < k.c.size(); ++j) sum += k.c[j] * std::exp(-k.u[j] * t);
        worst = std::max(worst, rel_err(sum, std::pow(t / t0, -beta)));
      }
      INFO("decades " << decades << ", beta " << beta << ": " << k.c.size() << " terms, error " << worst);
      CHECK(worst < detail::kPowerLawKernelError);
      CHECK(k.c.size() < 6 * decades + 40);
    }
  // d psi / d beta = -log(t/t0) psi, through the Jets of the weights.
  using J = ceres::Jet<double, 1>;
  const double beta = 0.23, t0 = 1.0;
  const auto k = detail::power_law_kernel<J>(J(beta, 0), t0, 1e-3, 10.0);
  for (double t : {1e-3, 0.05, 1.0, 9.0}) {
    J sum(0.0);
    for (std::size_t j = 0; j < k.c.size(); ++j) sum += k.c[j] * exp(-k.u[j] * t);
    const double exact = -std::log(t / t0) * std::pow(t / t0, -beta);
    INFO("t = " << t);
    CHECK(std::abs(sum.v[0] - exact) < 1e-8 * std::max(1.0, std::abs(exact)));
  }
  // And the exact integral of the newest piece, with its derivative.
  const J I = k.integral(J(0.0), J(0.01));
  CHECK(rel_err(I.a, std::pow(0.01, 1.0 - beta) / (1.0 - beta)) < 1e-14);
}

TEST_CASE("a power-law paraboloid: loading and Ting's unloading match Efremov's closed forms to 1e-6", "[viscoelastic]") {
  const double beta = 0.2, t0 = 1.0;
  const Triangle tri{2e-6, 2e-6, 0.5};  // 1 um at 2 um/s, back at the same speed
  const RelaxationLaw law = RelaxationLaw::power_law(beta, t0);
  const double C = 2.0 * kEstar * std::sqrt(kR) * std::pow(tri.v, 1.5) * std::pow(t0, beta);
  const auto loading = [&](double t) { return C * boost::math::beta(1.5, 1.0 - beta) * std::pow(t, 1.5 - beta); };
  // (t - t1)^(1-b) = (1 + v_r/v) (t - t_m)^(1-b); P = C int_0^t1 s^(1/2) (t - s)^-b ds = C t^(3/2-b) B(t1/t; 3/2, 1-b).
  const double ratio = std::pow(1.0 + tri.v_r / tri.v, 1.0 / (1.0 - beta));
  const auto t1_of = [&](double t) { return t - ratio * (t - tri.t_m); };
  const auto unloading = [&](double t) {
    const double t1 = t1_of(t);
    return t1 <= 0.0 ? 0.0 : C * std::pow(t, 1.5 - beta) * boost::math::beta(1.5, 1.0 - beta, t1 / t);
  };
  const double t_lost = ratio * tri.t_m / (ratio - 1.0);  // t1 = 0
  double previous_load = 0.0, previous_unload = 0.0;
  for (int n : {2000, 8000, 32000}) {
    const History h = sample(tri, 1.2 * tri.t_m * 2.0, n);
    const HereditaryResponse r = hereditary_response(h.t, h.delta, hertz, law);
    double worst_load = 0.0, worst_unload = 0.0, worst_t1 = 0.0;
    for (std::size_t i = 0; i < h.t.size(); ++i) {
      const double t = h.t[i];
      if (t >= 0.1 * tri.t_m && t <= tri.t_m) worst_load = std::max(worst_load, rel_err(r.P[i], loading(t)));
      if (t > tri.t_m * 1.02 && t < 0.98 * t_lost) {
        worst_unload = std::max(worst_unload, rel_err(r.P[i], unloading(t)));
        worst_t1 = std::max(worst_t1, std::abs(r.t1[i] - t1_of(t)) / tri.t_m);
        CHECK(r.delta1[i] == Approx(tri.delta(t1_of(t))).epsilon(1e-3));
      }
      if (t > 1.01 * t_lost) {
        CHECK(r.P[i] == 0.0);  // the contact is lost where t1 reaches the first contact
        CHECK(std::isnan(r.t1[i]));
      }
    }
    INFO("n = " << n << ": loading " << worst_load << ", unloading " << worst_unload << ", t1 " << worst_t1);
    if (previous_load > 0.0) {
      CHECK(worst_load < previous_load / 8.0);
      CHECK(worst_unload < previous_unload / 3.0);
    }
    previous_load = worst_load;
    previous_unload = worst_unload;
    CHECK(worst_t1 < 1e-5);
  }
  CHECK(previous_load < 1e-6);
  CHECK(previous_unload < 1e-6);
}

TEST_CASE("a standard linear solid: Ting's unloading against quadrature and a bracketed t1", "[viscoelastic]") {
  const double ratio = 0.3, tau = 0.15;
  const RelaxationLaw law = RelaxationLaw::standard_linear_solid(ratio, tau);
  const Triangle tri{2e-6, 5e-6, 0.4};
  const History h = sample(tri, 0.8, 8000);
  const HereditaryResponse r = hereditary_response(h.t, h.delta, hertz, law);
  using GK = boost::math::quadrature::gauss_kronrod<double, 61>;
  const auto psi = [&](double s) { return law.relative_modulus(s); };
  const auto rate = [&](double s) {  // dP_H/ds while loading
    return 2.0 * kEstar * std::sqrt(kR) * std::sqrt(tri.delta(s)) * tri.v;
  };
  for (std::size_t i = 400; i < h.t.size(); i += 400) {
    const double t = h.t[i];
    double t1 = t, P = 0.0;
    if (t > tri.t_m) {
      // int_t1^t psi(t - s) d delta(s) = 0: v int_t1^tm psi - v_r int_tm^t psi.
      const double back = tri.v_r * GK::integrate([&](double s) { return psi(t - s); }, tri.t_m, t, 15, 1e-14);
      const auto phi = [&](double s) {
        return tri.v * GK::integrate([&](double u) { return psi(t - u); }, s, tri.t_m, 15, 1e-14) - back;
      };
      if (phi(0.0) < 0.0) {
        t1 = 0.0;
      } else {
        std::uintmax_t it = 200;
        const auto root = boost::math::tools::toms748_solve(phi, 0.0, tri.t_m, boost::math::tools::eps_tolerance<double>(50), it);
        t1 = 0.5 * (root.first + root.second);
      }
    }
    if (t1 > 0.0) P = GK::integrate([&](double s) { return psi(t - s) * rate(s); }, 0.0, t1, 15, 1e-14);
    INFO("t = " << t << ", t1 = " << t1);
    if (P == 0.0) {
      CHECK(r.P[i] == 0.0);
    } else {
      CHECK(rel_err(r.P[i], P) < 2e-6);
      CHECK(std::abs(r.t1[i] - t1) < 1e-6 * tri.t_m);
    }
  }
}

TEST_CASE("hereditary response: the elastic limits load and unload along the elastic curve", "[viscoelastic]") {
  const Triangle tri{2e-6, 3e-6, 0.5};
  const History h = sample(tri, 0.8, 400);
  // Unloading retraces the loading samples' P_H, linear in time between them - so in d, at the
  // sample's indentation: that chord is the elastic answer of a history sampled this way.
  const auto chord = [&](double d) {
    for (std::size_t i = 1; i < h.t.size() && h.t[i] <= tri.t_m; ++i)
      if (h.delta[i] >= d) {
        const double f = (d - h.delta[i - 1]) / (h.delta[i] - h.delta[i - 1]);
        return hertz(h.delta[i - 1]) + f * (hertz(h.delta[i]) - hertz(h.delta[i - 1]));
      }
    return 0.0;
  };
  const double scale = hertz(tri.delta(tri.t_m));
  const auto check_elastic = [&](const RelaxationLaw& law, double factor, double tolerance) {
    const HereditaryResponse r = hereditary_response(h.t, h.delta, hertz, law);
    double worst = 0.0;
    for (std::size_t i = 0; i < h.t.size(); ++i) {
      worst = std::max(worst, std::abs(r.P[i] - factor * chord(h.delta[i])) / (factor * scale));
      if (h.delta[i] > 0.0) CHECK(r.delta1[i] == Approx(h.delta[i]).epsilon(1e-6));
    }
    INFO(law.describe() << ": largest error " << worst << " of the largest force");
    CHECK(worst <= tolerance);
  };
  check_elastic(RelaxationLaw{}, 1.0, 1e-13);
  check_elastic(RelaxationLaw::power_law(0.0, 3.0), 1.0, 1e-9);
  check_elastic(RelaxationLaw::standard_linear_solid(0.25, 1e9), 1.0, 1e-8);
  check_elastic(RelaxationLaw::standard_linear_solid(0.25, 1e-9), 0.25, 1e-7);  // tau / dt of the newest piece unrelaxed
}

TEST_CASE("hereditary response: a dwell relaxes at the largest radius, a noisy history stays finite", "[viscoelastic]") {
  const RelaxationLaw law = RelaxationLaw::standard_linear_solid(0.4, 0.1);
  History h;
  for (int i = 0; i <= 600; ++i) {
    const double t = i * 1e-3;
    h.t.push_back(t);
    h.delta.push_back(t < 0.2 ? 5e-6 * (t - 0.01) : t < 0.4 ? 5e-6 * 0.19 : 5e-6 * (0.19 - (t - 0.4)));
  }
  const HereditaryResponse r = hereditary_response(h.t, h.delta, hertz, law);
  for (int i = 201; i < 400; ++i) {
    CHECK(r.P[i] < r.P[i - 1]);                        // relaxing
    CHECK(r.delta1[i] == Approx(5e-6 * 0.19));         // at the largest radius
  }
  CHECK(r.P[399] > 0.4 * hertz(5e-6 * 0.19));
  CHECK(r.delta1[420] < 5e-6 * 0.19);  // receding once the indenter withdraws
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 2e-9);
  History noisy = h;
  for (std::size_t i = 20; i < noisy.delta.size(); ++i) noisy.delta[i] += noise(rng);
  const HereditaryResponse rn = hereditary_response(noisy.t, noisy.delta, hertz, law);
  double worst = 0.0;
  for (std::size_t i = 0; i < h.t.size(); ++i) {
    REQUIRE(std::isfinite(rn.P[i]));
    worst = std::max(worst, std::abs(rn.P[i] - r.P[i]));
  }
  // 2 nm of noise on ~1 um: the force moves by the elastic stiffness times a few noise sigmas.
  CHECK(worst < 10.0 * 2.0 * kEstar * std::sqrt(kR * 1e-6) * 2e-9);
}

TEST_CASE("hereditary response: bad input names the sample and what is wrong", "[viscoelastic]") {
  const RelaxationLaw law = RelaxationLaw::standard_linear_solid(0.5, 1.0);
  CHECK_THROWS_WITH(hereditary_response({0.0, 1.0}, {1e-6, 2e-6}, hertz, law),
                    Catch::Contains("delta[0] = 1e-06 m is in contact") && Catch::Contains("start out of contact"));
  CHECK_THROWS_WITH(hereditary_response({0.0, 0.0}, {0.0, 1e-6}, hertz, law), Catch::Contains("t[1] = 0 s does not increase"));
  CHECK_THROWS_WITH(hereditary_response({0.0, 1.0}, {0.0}, hertz, law), Catch::Contains("different lengths"));
  CHECK_THROWS_WITH(hereditary_response({0.0, NAN}, {0.0, 1e-6}, hertz, law), Catch::Contains("t[1] or delta[1] is not finite"));
  CHECK_THROWS_WITH(hereditary_response({0.0, 1.0}, {0.0, 1e-6}, [](double) { return NAN; }, law),
                    Catch::Contains("elastic force at delta = 1e-06 m is not finite"));
  const HereditaryResponse none = hereditary_response({0.0, 1.0}, {-1e-6, -0.5e-6}, hertz, law);
  CHECK(none.P == std::vector<double>{0.0, 0.0});
}
