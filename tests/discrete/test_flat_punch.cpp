// Stage A of the two-model approach: flat-punch load steps to S_k, against models whose
// flat-punch stiffness is known in closed form, and the errors Condition 2 calls for.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

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
