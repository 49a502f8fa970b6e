// Maugis-Dugdale on the half-space (maugis_dugdale.hpp) against an independent 50-digit mpmath
// solution of the published equations (tools/maugis_reference.py: explicit in m, extrema as
// roots of d/dm), the JKR and DMT limits with their derived rates, the library's own JKR
// transform, and a published fit of the pull-off.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/jkr.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "layerjkr/model.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

const double kPi = 3.141592653589793238462643383279502884;

// data/adhesion/maugis_pull_off.csv: lambda, then A, m, C, Pbar, Deltabar at load-control
// pull-off and at the fixed-grips instability (nan where there is none).
// The comment line "# fixed-grips threshold lambda = X" gives X in *threshold.
std::vector<std::vector<double>> reference_rows(double* threshold = nullptr) {
  const std::string path = std::string(LAYERJKR_SOURCE_DIR) + "/data/adhesion/maugis_pull_off.csv";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::vector<double>> rows;
  std::string line;
  const std::string key = "# fixed-grips threshold lambda = ";
  while (std::getline(in, line)) {
    if (threshold && line.rfind(key, 0) == 0) *threshold = std::stod(line.substr(key.size()));
    if (line.empty() || line[0] == '#' || line.rfind("lambda,", 0) == 0) continue;
    std::stringstream cells(line);
    std::vector<double> row;
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    REQUIRE(row.size() == 11);
    rows.push_back(row);
  }
  return rows;
}

// The first equation in the published form with m (not s), in long double: how far a
// returned point is from solving it.
long double published_residual(double lambda, const MaugisPoint& p) {
  const long double m = p.m, A = p.A, l = lambda;
  const long double s = std::sqrt(m * m - 1.0L), t = std::acos(1.0L / m);
  return (l * A * A / 2) * (s + (m * m - 2) * t) + (4 * l * l * A / 3) * (s * t - m + 1) - 1.0L;
}

}  // namespace

TEST_CASE("Maugis-Dugdale pull-off and fixed grips against the 50-digit mpmath reference", "[adhesion]") {
  double threshold = 0.0;
  const auto rows = reference_rows(&threshold);
  REQUIRE(rows.size() >= 25);
  CHECK(rel_err(kMaugisFixedGripsLambda, threshold) < 1e-16);
  double worst_P = 0.0, worst_A = 0.0, worst_fg = 0.0;
  int fixed_grips = 0;
  for (const auto& r : rows) {
    const double lambda = r[0];
    const MaugisPoint p = maugis_pull_off(lambda);
    INFO("lambda = " << lambda << ": A = " << p.A << " (" << r[1] << "), P = " << p.P << " (" << r[4] << ")");
    worst_P = std::max(worst_P, rel_err(p.P, r[4]));
    worst_A = std::max(worst_A, rel_err(p.A, r[1]));
    // measured: P 7.4e-16, A 7.4e-12 (at lambda = 1e-4; 4e-13 from 0.01 up)
    CHECK(rel_err(p.P, r[4]) < 1e-14);
    CHECK(rel_err(p.Delta, r[5]) < 1e-10);
    CHECK(rel_err(p.A, r[1]) < 1e-10);
    CHECK(rel_err(p.C, r[3]) < 1e-10);
    CHECK(rel_err(p.m, r[2]) < 1e-10);
    const auto fg = maugis_fixed_grips(lambda);
    if (std::isnan(r[6])) {
      CHECK_FALSE(fg.has_value());
      CHECK(lambda < kMaugisFixedGripsLambda);
    } else {
      REQUIRE(fg.has_value());
      ++fixed_grips;
      INFO("fixed grips: A = " << fg->A << " (" << r[6] << "), Delta = " << fg->Delta << " (" << r[10] << ")");
      worst_fg = std::max({worst_fg, rel_err(fg->A, r[6]), rel_err(fg->P, r[9])});
      CHECK(rel_err(fg->Delta, r[10]) < 1e-13);
      CHECK(rel_err(fg->A, r[6]) < 1e-11);  // measured 3.3e-13 (lambda = 0.94, A = 0.0035)
      CHECK(rel_err(fg->P, r[9]) < 1e-11);
      CHECK(rel_err(fg->C, r[8]) < 1e-11);
    }
  }
  CHECK(fixed_grips >= 20);
  WARN("worst relative error: pull-off P " << worst_P << ", A " << worst_A << "; fixed grips A, P " << worst_fg);
}

TEST_CASE("Maugis-Dugdale limits: DMT as lambda -> 0 and JKR as lambda -> infinity, at the derived rates", "[adhesion]") {
  // lambda -> 0: Pbar = -2 + k lambda^(3/2) + ..., k = 16 (pi/2 - 1) / (3 sqrt(pi)) (the
  // no-contact state's quadratic in C, expanded); the pull-off radius A -> 2 pi lambda / 3.
  const double k = 16.0 * (kPi / 2 - 1) / (3.0 * std::sqrt(kPi));
  for (double lambda : {1e-4, 1e-3}) {
    const MaugisPoint p = maugis_pull_off(lambda);
    INFO("lambda = " << lambda << ": Pbar = " << p.P);
    CHECK(std::abs(p.P + 2.0) < 2 * k * std::pow(lambda, 1.5));
    CHECK(rel_err(p.P + 2.0, k * std::pow(lambda, 1.5)) < 2e-3 * std::sqrt(lambda / 1e-4));
    CHECK(rel_err(p.A, 2 * kPi * lambda / 3) < 10 * lambda);
  }
  // lambda -> infinity: Pbar = -3/2 - (3/2)^(5/3) / (12 lambda^2), at A -> (3/2)^(1/3).
  for (double lambda : {1e3, 1e4}) {
    const MaugisPoint p = maugis_pull_off(lambda);
    const double rate = std::pow(1.5, 5.0 / 3.0) / 12.0;
    INFO("lambda = " << lambda << ": Pbar = " << p.P);
    CHECK(rel_err(p.P + 1.5, -rate / (lambda * lambda)) < 1e-2);
    CHECK(rel_err(p.A, std::cbrt(1.5)) < 1e-5);
    const auto fg = maugis_fixed_grips(lambda);
    REQUIRE(fg.has_value());
    CHECK(rel_err(fg->P, -5.0 / 6.0) < 1e-6);
    CHECK(rel_err(fg->A, std::cbrt(1.0 / 6.0)) < 1e-5);
  }
  // The whole curve: DMT's Pbar = A^3 - 2 and Deltabar = A^2 at small lambda; JKR's
  // Pbar = A^3 - sqrt(6 A^3), Deltabar = A^2 - (2/3) sqrt(6 A) at large.
  for (double A : {0.05, 0.3, 1.0, 2.0, 5.0}) {
    const MaugisPoint d = maugis_point(1e-4, A);
    INFO("A = " << A);
    // the first correction is the -pi lambda A^2 found at A = 0
    INFO("DMT: " << d.P - (A * A * A - 2.0) << ", JKR: " << maugis_point(1e4, A).P - (A * A * A - std::sqrt(6 * A * A * A)));
    CHECK(std::abs(d.P - (A * A * A - 2.0)) < 1.1 * kPi * 1e-4 * A * A + 1e-5);
    CHECK(std::abs(d.Delta - A * A) < 2e-2 * std::max(1.0, A));
    const MaugisPoint j = maugis_point(1e4, A);
    CHECK(std::abs(j.P - (A * A * A - std::sqrt(6 * A * A * A))) < 1e-7 * std::max(1.0, A * A * A));
    CHECK(std::abs(j.Delta - (A * A - 2.0 / 3.0 * std::sqrt(6 * A))) < 1e-7 * std::max(1.0, A * A));
  }
}

TEST_CASE("Maugis-Dugdale at lambda = 1e4 is the library's JKR transform on the half-space", "[adhesion]") {
  const double E = 2e9, nu = 0.35, R = 30e-9, w = 0.05, E_star = E / (1 - nu * nu);
  // sigma0 for lambda = 1e4: lambda = 2 sigma0 (R / (pi w K^2))^(1/3).
  const double K = 4 * E_star / 3;
  const double sigma0 = 1e4 / (2 * std::cbrt(R / (kPi * w * K * K)));
  REQUIRE(rel_err(maugis_lambda(R, E_star, w, sigma0), 1e4) < 1e-14);
  const auto model = make_half_space(make_paraboloid(R), E, nu);
  const CriticalPoint po = maugis_dugdale_pull_off(R, E_star, w, sigma0);
  CHECK(rel_err(po.P, -1.5 * kPi * w * R) < 1e-8);
  for (double factor : {0.3, 1.0, 2.0, 4.0}) {
    const double a = factor * po.a;
    const AdhesiveState md = maugis_dugdale_half_space(R, E_star, w, sigma0, a);
    const AdhesiveState jkr = jkr_transform(model->state(a), w);
    INFO("a = " << a << ": P = " << md.P << " (JKR " << jkr.P << ")");
    INFO("dP/(pi w R) = " << (md.P - jkr.P) / (kPi * w * R) << ", d delta / delta scale = " << (md.delta - jkr.delta) / std::abs(jkr.hertz.delta_H - jkr.delta));
    // at fixed A the Dugdale correction is (3/2 A^2 - 1.99 A^(1/2)) / lambda^2 of pi w R (docs/theory.md)
    const double A = a / std::cbrt(kPi * w * R * R / K);
    CHECK(std::abs(md.P - jkr.P) < 2e-8 * (1 + A * A) * kPi * w * R);
    CHECK(std::abs(md.delta - jkr.delta) < 1e-7 * std::abs(jkr.hertz.delta_H - jkr.delta));
    CHECK(md.c > a);
    CHECK(md.c < a * (1 + 1e-4));  // the Dugdale zone shrinks to the edge
    // hertz is the Hertz state at a, as the half-space model computes it
    CHECK(rel_err(md.hertz.P_H, jkr.hertz.P_H) < 1e-14);
    CHECK(rel_err(md.hertz.delta_H, jkr.hertz.delta_H) < 1e-14);
    CHECK(rel_err(md.hertz.S, jkr.hertz.S) < 1e-14);
    CHECK(rel_err(md.hertz.dS_da, jkr.hertz.dS_da) < 1e-14);
  }
}

TEST_CASE("Maugis-Dugdale points solve the published equation with m > 1 and are continuous at A = 0", "[adhesion]") {
  for (double lambda : {1e-4, 1e-2, 0.3, 1.0, 3.0, 100.0, 1e4}) {
    for (double A : {1e-12, 1e-6, 1e-3, 0.1, 0.5, 1.0, 2.0, 10.0, 1e3}) {
      const MaugisPoint p = maugis_point(lambda, A);
      INFO("lambda = " << lambda << ", A = " << A << ": m = " << p.m);
      CHECK(p.m > 1.0);
      CHECK(rel_err(p.C, p.m * A) < 1e-14);
      // m - 1 below 1e-8 cannot be written in m itself; above it, the equation holds in m
      if (p.m - 1.0 > 1e-8) CHECK(std::abs(published_residual(lambda, p)) < 1e-12 * std::max(1.0, 1.0 / (p.m - 1.0)));
    }
    const MaugisPoint zero = maugis_point(lambda, 0.0);
    CHECK(std::isinf(zero.m));
    CHECK(zero.A == 0.0);
    CHECK(rel_err(zero.P, -0.5 * kPi * lambda * zero.C * zero.C) < 1e-15);
    for (double f : {1e-3, 1e-5, 1e-7}) {
      // A small against the no-contact zone C(0) (which is ~1/lambda^2 at large lambda):
      // Pbar(A) = Pbar(0) - pi lambda A^2 + A^3 + ..., Deltabar(A) = Deltabar(0) + A^2 + ...,
      // C(A) = C(0) (1 + O(A^2/C^2)): no term linear in A.
      const double A = f * zero.C;
      const MaugisPoint p = maugis_point(lambda, A);
      INFO("lambda = " << lambda << ", A = " << A);
      CHECK(std::abs(p.P - zero.P) < A * A * A + 4 * kPi * lambda * A * A + 1e-15 * std::abs(zero.P));
      CHECK(std::abs(p.C - zero.C) < 10 * f * f * zero.C + 1e-14 * zero.C);
      CHECK(std::abs(p.Delta - zero.Delta) < 2 * A * A + 10 * f * f * std::abs(zero.Delta) + 1e-14 * std::abs(zero.Delta));
    }
    // below 1e-200 the limit is exact in double; the step there is invisible
    CHECK(maugis_point(lambda, 1e-201).P == zero.P);
    CHECK(rel_err(maugis_point(lambda, 1e-199).P, zero.P) < 1e-15);
  }
}

TEST_CASE("Maugis-Dugdale branches: dP/dDelta changes sign at the extrema the solver found", "[adhesion]") {
  for (double lambda : {0.05, 0.5, 1.5, 10.0}) {
    const MaugisPoint po = maugis_pull_off(lambda);
    const auto fg = maugis_fixed_grips(lambda);
    const auto slopes = [&](double A) {
      const double h = 1e-6 * A;
      const MaugisPoint lo = maugis_point(lambda, A - h), hi = maugis_point(lambda, A + h);
      return std::pair<double, double>{(hi.P - lo.P) / (2 * h), (hi.Delta - lo.Delta) / (2 * h)};
    };
    // The pull-off is the global minimum of P: no point of a fine scan lies below it.
    for (int i = 0; i <= 400; ++i) {
      const double A = 1e-3 * std::pow(10.0, 6.0 * i / 400);
      CHECK(maugis_point(lambda, A).P >= po.P);
    }
    // Beyond the pull-off both P and Delta rise: stable under either control, dP/dDelta > 0.
    for (double f : {1.01, 1.5, 3.0}) {
      const auto [dP, dD] = slopes(f * po.A);
      INFO("lambda = " << lambda << ", A = " << f * po.A);
      CHECK(dP > 0.0);
      CHECK(dD > 0.0);
    }
    const auto [dP_below, dD_below] = slopes(0.9 * po.A);
    CHECK(dP_below < 0.0);
    if (fg) {
      // Between the fixed-grips point and the pull-off: P falls while Delta rises.
      CHECK(fg->A < po.A);
      const auto [dP, dD] = slopes(0.5 * (fg->A + po.A));
      CHECK(dP < 0.0);
      CHECK(dD > 0.0);
      const auto [dP2, dD2] = slopes(0.9 * fg->A);
      CHECK(dD2 < 0.0);
    } else {
      // No fixed-grips instability: Delta rises from A = 0 on.
      for (double A : {1e-3, 0.01, 0.1, 1.0}) CHECK(slopes(A).second > 0.0);
    }
  }
}

TEST_CASE("Maugis-Dugdale pull-off against the Pietrement-Troyon fit, lambda in [0.01, 100]", "[adhesion]") {
  // Pbar = -7/4 + (1/4)(4.04 lambda^1.4 - 1)/(4.04 lambda^1.4 + 1) (Pietrement & Troyon 2000,
  // quoted with Carpick-Ogletree-Salmeron 1999's transition curve): a fit, measured here to
  // 1.63 % at worst (lambda ~ 0.3), 0.1 % at lambda = 1.
  double worst = 0.0;
  for (int i = 0; i <= 32; ++i) {
    const double lambda = std::pow(10.0, -2.0 + i / 8.0);
    const double x = 4.04 * std::pow(lambda, 1.4);
    const double fit = -1.75 + 0.25 * (x - 1) / (x + 1);
    worst = std::max(worst, rel_err(fit, maugis_pull_off(lambda).P));
  }
  CHECK(worst < 0.017);
  CHECK(worst > 0.015);  // the fit's own error, not ours: a much smaller number would be suspicious
}

TEST_CASE("Maugis lambda, Tabor mu and the Lennard-Jones Dugdale stress", "[adhesion]") {
  const double R = 20e-9, E_star = 1e9, w = 0.1, z0 = 0.3e-9;
  const double mu = tabor_parameter(R, E_star, w, z0);
  CHECK(rel_err(mu, std::cbrt(R * w * w / (E_star * E_star * z0 * z0 * z0))) < 1e-15);
  const double sigma0 = lennard_jones_dugdale_stress(w, z0);
  CHECK(rel_err(sigma0, 16 * w / (9 * std::sqrt(3.0) * z0)) < 1e-15);
  // lambda / mu = (32 / (9 sqrt 3)) (3/4)^(2/3) pi^(-1/3) = 1.1570...
  const double ratio = maugis_lambda(R, E_star, w, sigma0) / mu;
  CHECK(rel_err(ratio, 32 / (9 * std::sqrt(3.0)) * std::pow(0.75, 2.0 / 3.0) / std::cbrt(kPi)) < 1e-14);
  CHECK(std::abs(ratio - 1.1570) < 5e-5);
  // The dimensional state is the dimensionless one scaled: a = A l, P = Pbar pi w R, ...
  const double lambda = maugis_lambda(R, E_star, w, sigma0);
  const double K = 4 * E_star / 3, l = std::cbrt(kPi * w * R * R / K);
  const MaugisPoint p = maugis_point(lambda, 0.7);
  const AdhesiveState s = maugis_dugdale_half_space(R, E_star, w, sigma0, 0.7 * l);
  CHECK(rel_err(s.P, p.P * kPi * w * R) < 1e-13);
  CHECK(rel_err(s.c, p.C * l) < 1e-13);
  CHECK(rel_err(s.delta, p.Delta * std::cbrt(kPi * kPi * w * w * R / (K * K))) < 1e-13);
  const auto fg = maugis_dugdale_fixed_grips(R, E_star, w, sigma0);
  CHECK(fg.has_value() == maugis_fixed_grips(lambda).has_value());
  const AdhesiveState none = maugis_dugdale_half_space(R, E_star, w, sigma0, 0.0);
  CHECK(none.P < 0.0);
  CHECK(none.c > 0.0);
  CHECK(none.hertz.P_H == 0.0);
}

TEST_CASE("Maugis-Dugdale rejects bad input naming the parameter, value and range", "[adhesion][errors]") {
  CHECK_THROWS_WITH(maugis_point(1e-5, 1.0), Catch::Contains("lambda = 1e-05") &&
                                                 Catch::Contains("[1e-4, 1e4]"));
  CHECK_THROWS_AS(maugis_point(2e4, 1.0), DomainError);
  CHECK_THROWS_AS(maugis_point(NAN, 1.0), DomainError);
  CHECK_THROWS_WITH(maugis_point(1.0, -0.5), Catch::Contains("A = -0.5") && Catch::Contains(">= 0"));
  CHECK_THROWS_AS(maugis_point(1.0, INFINITY), DomainError);
  CHECK_THROWS_AS(maugis_point(1.0, NAN), DomainError);
  CHECK_THROWS_AS(maugis_pull_off(0.0), DomainError);
  CHECK_THROWS_AS(maugis_fixed_grips(INFINITY), DomainError);
  CHECK_THROWS_WITH(maugis_lambda(-1.0, 1e9, 0.1, 1e8), Catch::Contains("R = -1"));
  CHECK_THROWS_WITH(maugis_lambda(1e-8, 1e9, 0.1, 0.0), Catch::Contains("sigma0 = 0"));
  CHECK_THROWS_WITH(tabor_parameter(1e-8, 1e9, 0.1, -1e-10), Catch::Contains("z0"));
  CHECK_THROWS_WITH(lennard_jones_dugdale_stress(0.0, 1e-10), Catch::Contains("w = 0"));
  CHECK_THROWS_WITH(maugis_dugdale_half_space(1e-8, 1e9, 0.1, 1e8, -1e-9), Catch::Contains("a = -1"));
  // lambda out of range from physical inputs: the message says which combination
  CHECK_THROWS_WITH(maugis_dugdale_pull_off(1e-8, 1e9, 0.1, 1e3), Catch::Contains("lambda"));
  CHECK_THROWS_AS(maugis_dugdale_fixed_grips(1e-8, 1e9, NAN, 1e8), DomainError);
}
