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
    const NonAdhesiveState s = model.state(a_max * i / n);
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
    const NonAdhesiveState d = model->state(a), t = winkler->state(a);
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
    const NonAdhesiveState d = model->state(a), t = exact->state(a);
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
    DiscreteOptions tolerant;
    tolerant.linearity_tolerance = 0.05;
    const auto two = make_discrete_model(steps_from(*exact, radii, 5e-3, seed), convex, tolerant);
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

TEST_CASE("synthetic data: Winkler's closed forms, the mesh-rounded radius and bad sampling", "[discrete]") {
  // Winkler paraboloid: flat punch P = pi K a^2 delta; sphere-free convex P = pi K R delta^2,
  // a = sqrt(2 R delta).
  const double K = 4e10, R = 1e-2;
  const auto winkler = make_winkler(make_paraboloid(R), K);
  const FlatPunchData flat = sample_flat_punch(*winkler, {1e-4, 2e-4}, {5, 1e-6});
  REQUIRE(flat.a.size() == 10);
  CHECK(rel_err(flat.P[9], M_PI * K * 4e-8 * 1e-6) < 1e-14);
  const ConvexData convex = sample_convex(*winkler, {8, 2e-6});
  REQUIRE(convex.delta.size() == 8);
  for (std::size_t i = 0; i < 8; ++i) {
    CHECK(rel_err(convex.P[i], M_PI * K * R * convex.delta[i] * convex.delta[i]) < 1e-12);
    CHECK(rel_err(convex.a[i], std::sqrt(2 * R * convex.delta[i])) < 1e-12);
  }
  const ConvexData meshed = sample_convex(*winkler, {8, 2e-6, 0.0, 1, 5e-6});
  for (double a : meshed.a) CHECK(std::abs(a / 5e-6 - std::round(a / 5e-6)) < 1e-9);
  CHECK_THROWS_WITH(sample_convex(*winkler, {1, 2e-6}), Catch::Contains("load_steps"));
  CHECK_THROWS_WITH(sample_convex(*winkler, {8, -1.0}), Catch::Contains("delta_max"));
  CHECK_THROWS_WITH(sample_convex(*winkler, {8, 1e-6, 0.9}), Catch::Contains("noise"));
}

TEST_CASE("log-log fits: power laws exactly, smooth curves to their cross-validated accuracy", "[discrete]") {
  std::vector<double> x, power, layer;
  for (int i = 1; i <= 20; ++i) {
    x.push_back(1e-4 * i);
    power.push_back(3.0 * std::pow(x.back(), 2.5));
    layer.push_back(x.back() * x.back() * (1.0 + 1e-4 / x.back()));  // Winkler with an edge term
  }
  for (Smoothing smoothing : {Smoothing::log_polynomial, Smoothing::log_spline}) {
    const auto p = fit_log_log(x, power, smoothing, 3, "power");
    CHECK(rel_err(p->value(3.3e-4), 3.0 * std::pow(3.3e-4, 2.5)) < 1e-12);
    CHECK(std::abs(p->log_slope(7.7e-4) - 2.5) < 1e-10);
    CHECK(std::abs(p->log_curvature(1.5e-3)) < 1e-8);
    const auto l = fit_log_log(x, layer, smoothing, 3, "layer");
    INFO(l->complexity());
    const double at = 5.5e-4, slope = 2.0 - 1e-4 / at / (1.0 + 1e-4 / at);
    CHECK(rel_err(l->value(at), at * at * (1.0 + 1e-4 / at)) < 1e-3);
    CHECK(std::abs(l->log_slope(at) - slope) < 1e-2);
  }
  CHECK_THROWS_WITH(fit_log_log({1, 2, 3}, {1, 2, 3}, Smoothing::log_spline, 3, "three"), Catch::Contains("4 or more"));
  CHECK_THROWS_WITH(fit_log_log({1, 1, 1, 1}, {1, 2, 3, 4}, Smoothing::log_polynomial, 3, "same"), Catch::Contains("same abscissa"));
}

TEST_CASE("bootstrap: the error bars cover the truth and vanish without noise", "[discrete]") {
  // Exact-layer data (the bundled set's recipe, 0.3 % noise): over 10 noise seeds the pull-off
  // force lands within 3 bootstrap standard deviations of the truth in 9 or more. Noiseless data
  // leave only the smoothing's misfit as residuals: 0.02 % against 0.3 % with noise.
  const ElasticLayer layer{3e6, 0.3, 0.1e-3, Base::bonded};
  const auto truth = make_exact_layer(make_sphere(10e-3), layer);
  const std::vector<double> radii{0.1e-3, 0.2e-3, 0.3e-3, 0.4e-3, 0.5e-3, 0.6e-3};
  const double w = 0.2, P_true = JkrSolution(truth, w).pull_off()->P;
  int covered = 0;
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const FlatPunchData flat = sample_flat_punch(*truth, radii, {20, 0.025e-3, 0.003, seed});
    const ConvexData convex = sample_convex(*truth, {20, 0.025e-3, 0.003, seed + 100, 5e-6});
    const DiscreteUncertainty u = bootstrap_discrete(flat, convex, w, {0.3e-3}, DiscreteApproach::two_models, {}, {100, seed});
    const double P = JkrSolution(make_discrete_model(flat, convex), w).pull_off()->P;
    INFO("seed " << seed << ": " << P << " +- " << u.pull_off_force_err << " vs " << P_true);
    CHECK(u.failed == 0);
    CHECK(u.used[0] == 100);
    CHECK(u.pull_off_force_err > 0.0);
    covered += std::abs(P - P_true) < 3.0 * u.pull_off_force_err;
  }
  CHECK(covered >= 9);
  const FlatPunchData flat = sample_flat_punch(*truth, radii, {20, 0.025e-3});
  const ConvexData convex = sample_convex(*truth, {20, 0.025e-3});
  const DiscreteUncertainty quiet = bootstrap_discrete(flat, convex, w, {0.3e-3}, DiscreteApproach::two_models);
  CHECK(std::abs(quiet.pull_off_force_err / P_true) < 5e-4);
  CHECK_THROWS_WITH(bootstrap_discrete(flat, convex, w, {}, DiscreteApproach::two_models, {}, {5, 1}), Catch::Contains("replicates"));
  CHECK_THROWS_WITH(make_discrete_model(flat, convex, [] {
                      DiscreteOptions o;
                      o.max_degree = 9;
                      return o;
                    }()),
                    Catch::Contains("max_degree"));
}

TEST_CASE("Appendix A workflow: (delta*, P*) at a* = 0.4 mm from exact-layer data at the paper's sampling", "[discrete]") {
  // The paper's Steps 1-3 with the exact layer standing in for its FEM: flat punches and a
  // 10 mm sphere, 20 substeps to 0.025 mm each, noiseless. Measured: S* -0.003 %, delta*
  // -0.022 %, P* -0.067 % (the paper's FEM check of its own workflow: 0.098 % in P).
  const auto exact = make_exact_layer(make_sphere(10e-3), {3e6, 0.3, 0.1e-3, Base::bonded});
  const SyntheticSampling steps{20, 0.025e-3};
  const auto rebuilt = make_discrete_model(sample_flat_punch(*exact, {0.2e-3, 0.3e-3, 0.4e-3, 0.5e-3, 0.6e-3}, steps),
                                           sample_convex(*exact, steps));
  const NonAdhesiveState t = exact->state(0.4e-3), r = rebuilt->state(0.4e-3);
  CHECK(rel_err(r.S, t.S) < 1e-4);
  CHECK(rel_err(r.delta_H, t.delta_H) < 5e-4);
  CHECK(rel_err(r.P_H, t.P_H) < 1e-3);
}
