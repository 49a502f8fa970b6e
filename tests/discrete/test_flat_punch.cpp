// Stage A of the two-model approach: flat-punch load steps to S_k, against models whose
// flat-punch stiffness is known in closed form, and the errors Condition 2 calls for.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "layerjkr/contact.hpp"
#include "layerjkr/discrete.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
// FEM-like sampling: 20 load steps at each radius, forces with relative noise.
FlatPunchData steps_from(const ContactModel& model, const std::vector<double>& radii, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  FlatPunchData d;
  for (double a : radii) {
    const double S = model.state(a).S;
    for (int i = 1; i <= 20; ++i) {
      const double delta = 1e-6 * i;
      d.a.push_back(a);
      d.delta.push_back(delta);
      d.P.push_back(S * delta * (1.0 + noise * gauss(rng)));
    }
  }
  return d;
}
}  // namespace

TEST_CASE("flat punch: S_k of the exact layer and of Winkler, within their error bars", "[discrete]") {
  const std::vector<double> radii{2e-4, 4e-4, 6e-4, 8e-4, 1e-3, 1.2e-3};
  const ElasticLayer layer{3e6, 0.3, 1e-4, Base::bonded};
  const auto exact = make_exact_layer(make_paraboloid(1e-2), layer);
  const FlatPunchStiffness noiseless = fit_flat_punch(steps_from(*exact, radii, 0.0, 1));
  REQUIRE(noiseless.S.size() == radii.size());
  for (std::size_t k = 0; k < radii.size(); ++k) {
    CHECK(noiseless.a[k] == radii[k]);
    CHECK(rel_err(noiseless.S[k], exact->state(radii[k]).S) < 1e-12);
    CHECK(noiseless.nonlinearity[k] < 1e-12);
  }
  const auto winkler = make_winkler(make_paraboloid(1e-2), thin_layer_constants(layer).K);
  const FlatPunchStiffness noisy = fit_flat_punch(steps_from(*winkler, radii, 0.005, 2), 0.05);
  for (std::size_t k = 0; k < radii.size(); ++k) {
    INFO("a = " << radii[k]);
    CHECK(std::abs(noisy.S[k] - winkler->state(radii[k]).S) < 4.0 * noisy.S_stderr[k]);
    CHECK(noisy.S_stderr[k] > 0.0);
  }
}

TEST_CASE("flat punch: data that breaks Condition 2 or is too sparse is rejected, naming the radius", "[discrete][errors]") {
  const std::string head = "a,delta,P\n";
  auto rows = [](double a, double curvature) {
    std::string s;
    for (int i = 1; i <= 5; ++i) {
      const double d = 1e-6 * i;
      s += format_double(a) + "," + format_double(d) + "," + format_double(1e3 * a * d * (1.0 + curvature * i)) + "\n";
    }
    return s;
  };
  const std::string good = rows(0.001, 0) + rows(0.002, 0) + rows(0.003, 0) + rows(0.004, 0);
  CHECK(fit_flat_punch(parse_flat_punch_csv(head + good, "ok")).S.size() == 4);
  CHECK_THROWS_WITH(fit_flat_punch(parse_flat_punch_csv(head + rows(0.001, 0) + rows(0.002, 0) + rows(0.003, 0), "few")),
                    Catch::Contains("3 radii") && Catch::Contains("4 or more"));
  CHECK_THROWS_WITH(fit_flat_punch(parse_flat_punch_csv(head + good + rows(0.005, 0.5), "bent")),
                    Catch::Contains("a = 0.005") && Catch::Contains("not linear"));
  CHECK_THROWS_WITH(parse_flat_punch_csv("a,delta\n1,2\n", "cols"), Catch::Contains("a, delta and P"));
  CHECK_THROWS_WITH(parse_flat_punch_csv(head + "0.001,nan,1\n", "nan"), Catch::Contains("line 2") && Catch::Contains("nan"));
  CHECK_THROWS_WITH(parse_flat_punch_csv(head + "-0.001,1e-6,1\n", "neg"), Catch::Contains("a = -0.001"));
  CHECK_THROWS_WITH(fit_flat_punch(parse_flat_punch_csv(head + good, "tol"), 0.0), Catch::Contains("linearity_tolerance"));
  // S_k that falls with the radius is not a flat punch on a layer.
  const std::string falling = rows(0.001, 0) + rows(0.002, 0) + rows(0.003, 0) + [] {
    std::string s;
    for (int i = 1; i <= 5; ++i) s += "0.004," + format_double(1e-6 * i) + "," + format_double(1.0 * 1e-6 * i) + "\n";
    return s;
  }();
  CHECK_THROWS_WITH(fit_flat_punch(parse_flat_punch_csv(head + falling, "falling")), Catch::Contains("does not grow with the radius"));
}

namespace {
ConvexData convex_from(const ContactModel& model, double a_max, int n, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  ConvexData c;
  for (int i = 1; i <= n; ++i) {
    const HertzState s = model.state(a_max * i / n);
    c.delta.push_back(s.delta_H);
    c.P.push_back(s.P_H * (1.0 + noise * gauss(rng)));
    c.a.push_back(s.a);
  }
  return c;
}
}  // namespace

TEST_CASE("two-model approach: Winkler data give Winkler back, and its JKR pull-off -2 pi w R", "[discrete]") {
  const double K = 4e10, R = 1e-2, w = 0.05;
  const auto winkler = make_winkler(make_paraboloid(R), K);
  const std::vector<double> radii{1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4};
  const auto model = make_discrete_model(steps_from(*winkler, radii, 0.0, 1), convex_from(*winkler, 8e-4, 20, 0.0, 1));
  for (double a : {1.5e-4, 3.3e-4, 5.5e-4}) {
    const HertzState d = model->state(a), t = winkler->state(a);
    INFO("a = " << a);
    CHECK(rel_err(d.delta_H, t.delta_H) < 1e-9);
    CHECK(rel_err(d.P_H, t.P_H) < 1e-9);
    CHECK(rel_err(d.S, t.S) < 1e-9);
    CHECK(rel_err(d.dS_da, t.dS_da) < 1e-9);
  }
  const auto po = JkrSolution(model, w).pull_off();
  REQUIRE(po);
  CHECK(rel_err(po->P, -2.0 * M_PI * w * R) < 1e-8);
  CHECK_THROWS_WITH(model->state(9e-4), Catch::Contains("contact radius a"));
}

TEST_CASE("two-model approach on the exact layer: the reconstruction error, measured", "[discrete]") {
  // FEM-like data from the exact layer (nu = 0.3, a/h 1 .. 6): 6 radii x 20 steps, 20 convex
  // points, noise 0.1 %. Measured: P_H within 1.3 %, S within 0.13 % inside the data's range
  // (log-log polynomials chosen by cross-validation; the smoothing study may do better).
  const ElasticLayer layer{3e6, 0.3, 1e-4, Base::bonded};
  const auto exact = make_exact_layer(make_paraboloid(1e-2), layer);
  const std::vector<double> radii{1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4};
  const auto model = make_discrete_model(steps_from(*exact, radii, 1e-3, 3), convex_from(*exact, 7e-4, 20, 1e-3, 4));
  double worst_P = 0.0, worst_S = 0.0;
  for (double a = 1.5e-4; a <= 5.5e-4; a += 0.5e-4) {
    const HertzState d = model->state(a), t = exact->state(a);
    worst_P = std::max(worst_P, rel_err(d.P_H, t.P_H));
    worst_S = std::max(worst_S, rel_err(d.S, t.S));
  }
  INFO("worst P_H " << worst_P << " worst S " << worst_S);
  CHECK(worst_P < 0.02);
  CHECK(worst_S < 0.003);
}

TEST_CASE("two models against one: the flat punch spares the second derivative", "[discrete]") {
  // The paper's claim (section 5), measured on exact-layer data with 0.5 % noise on every
  // force: S' from the flat punch (one differentiation) against S' from the convex data alone
  // (two), and the JKR pull-off of each against the exact layer's.
  const ElasticLayer layer{3e6, 0.3, 1e-4, Base::bonded};
  const auto exact = make_exact_layer(make_paraboloid(1e-2), layer);
  const std::vector<double> radii{1e-4, 2e-4, 3e-4, 4e-4, 5e-4, 6e-4};
  double two_worst = 0.0, one_worst = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const ConvexData convex = convex_from(*exact, 7e-4, 20, 5e-3, 10 + seed);
    const auto two = make_discrete_model(steps_from(*exact, radii, 5e-3, seed), convex, {0.05, 3});
    const auto one = make_single_model(convex);
    for (double a = 1.5e-4; a <= 5.5e-4; a += 1e-4) {
      const double truth = exact->state(a).dS_da;
      two_worst = std::max(two_worst, rel_err(two->state(a).dS_da, truth));
      one_worst = std::max(one_worst, rel_err(one->state(a).dS_da, truth));
    }
  }
  INFO("worst S' error: two models " << two_worst << ", one model " << one_worst);
  CHECK(two_worst < one_worst);
  CHECK(two_worst < 0.02);
}
