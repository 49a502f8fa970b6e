// The exact path for a model linear in its free parameters (src/fit/fit_linear.cpp): a Hertz fit
// with the contact point given is linear least squares in (E, P0), so the fit must equal the
// closed-form normal equations written here independently, and the trust-region solve it
// replaces; a medium that is not linear in its one free stiffness falls back to Ceres.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "layerjkr/fit.hpp"
#include "layerjkr/simulate.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

constexpr double kR = 20e-9, kNu = 0.5, kE = 2e3;

// An approach of 500 samples, 100 before the contact at delta = 0, baseline 3 pN, 5 pN noise.
CurveData hertz_approach(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 5e-12);
  CurveData c;
  for (int i = 0; i < 500; ++i) {
    const double d = -0.25e-6 + 1.25e-6 * i / 499.0;
    const double t = std::max(d, 0.0);
    c.delta.push_back(d);
    c.P.push_back(3e-12 + 4.0 / 3.0 * kE / (1.0 - kNu * kNu) * std::sqrt(kR) * std::pow(t, 1.5) + noise(rng));
  }
  c.segment.assign(500, 0);
  return c;
}

Scene hertz_scene(double E) {
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "half_space", "E": )" +
                     std::to_string(E) + R"(, "nu": 0.5}})");
}

}  // namespace

TEST_CASE("a fit linear in E and P0 is the normal equations' solution, from any start", "[fit][linear]") {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const CurveData c = hertz_approach(seed);
    // The oracle: P = P0 + E g with g = 4/3 sqrt(R) t^1.5 / (1 - nu^2); 2 x 2 normal equations.
    double sg = 0.0, sgg = 0.0, sp = 0.0, sgp = 0.0;
    const double n = static_cast<double>(c.P.size());
    for (std::size_t i = 0; i < c.P.size(); ++i) {
      const double g = 4.0 / 3.0 / (1.0 - kNu * kNu) * std::sqrt(kR) * std::pow(std::max(c.delta[i], 0.0), 1.5);
      sg += g;
      sgg += g * g;
      sp += c.P[i];
      sgp += g * c.P[i];
    }
    const double E_oracle = (n * sgp - sg * sp) / (n * sgg - sg * sg);
    const double P0_oracle = (sp - E_oracle * sg) / n;
    for (double start : {0.1 * kE, 3.0 * kE, 10.0 * kE}) {
      FitOptions o;
      o.free = {FitParameter::E, FitParameter::P0};
      const FitSummary s = fit(c, hertz_scene(start), o);
      INFO("seed " << seed << ", start " << start << "\n" << s.brief_report());
      CHECK(s.converged);
      CHECK_THAT(s.termination, Catch::Contains("linear least squares"));
      CHECK(rel_err(s[FitParameter::E].value, E_oracle) < 1e-10);
      CHECK(std::abs(s[FitParameter::P0].value - P0_oracle) < 1e-10 * 5e-12 * 100.0);
      // Its error bar: sigma^2 (J^T J)^-1 with the residual variance, as for every fit.
      CHECK(s[FitParameter::E].standard_error > 0.0);
      CHECK(s[FitParameter::E].standard_error < 0.01 * kE);
    }
  }
}

TEST_CASE("the linear path gives the trust-region solve's answer and error bars", "[fit][linear]") {
  // The same problem through Ceres: a Huber loss whose scale (1 uN) no residual (pN) reaches is
  // least squares, but a robust loss is never taken for linear, so Ceres solves it.
  const CurveData c = hertz_approach(9);
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::P0};
  const FitSummary exact = fit(c, hertz_scene(3.0 * kE), o);
  REQUIRE_THAT(exact.termination, Catch::Contains("linear least squares"));
  o.loss = LossType::huber;
  o.loss_scale = 1e-6;
  const FitSummary ceres = fit(c, hertz_scene(3.0 * kE), o);
  INFO(exact.brief_report() << "\n" << ceres.brief_report());
  REQUIRE(ceres.converged);
  CHECK_THAT(ceres.termination, !Catch::Contains("linear least squares"));
  for (FitParameter q : {FitParameter::E, FitParameter::P0}) {
    CHECK(rel_err(exact[q].value, ceres[q].value) < 1e-7);
    CHECK(rel_err(exact[q].standard_error, ceres[q].standard_error) < 1e-5);
  }
}

TEST_CASE("a medium not linear in its one free stiffness falls back to the trust-region solve", "[fit][linear]") {
  // Pasternak: P depends on K and G; with G fixed the force is not proportional to K.
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "pasternak", "K": 1e12, "G": 200}, "model": "full"})");
  SimulationOptions so;
  so.branch = Branch::approach;
  so.max_indentation = 5e-6;
  so.free_fraction = 0.2;
  const CurveData c = simulate_curve(truth, so);
  Scene guess = truth;
  guess.medium.K *= 3.0;
  FitOptions o;
  o.free = {FitParameter::K, FitParameter::P0};
  const FitSummary s = fit(c, guess, o);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK_THAT(s.termination, !Catch::Contains("linear least squares"));
  CHECK(rel_err(s[FitParameter::K].value, 1e12) < 1e-6);
}
