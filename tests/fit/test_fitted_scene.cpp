// fitted_scene (layerjkr/fit.hpp): a fit's values written into its scene. Oracles: the scene
// reader's own fields after the round trip, a stack's ratios, and a fit whose fitted scene gives
// back the curve it was fitted to.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

ParameterEstimate estimate(FitParameter q, double value, int curve = -1) {
  ParameterEstimate e;
  e.parameter = q;
  e.value = value;
  e.curve = curve;
  return e;
}

}  // namespace

TEST_CASE("fitted scene: each parameter lands in its key, delta0 and P0 stay with the data", "[fit][scene]") {
  const Scene s = parse_scene(R"({"indenter": {"shape": "sphere", "R": 1e-5},
      "medium": {"type": "layer", "E": 2000, "nu": 0.49, "h": 3e-6, "viscoelastic": {"law": "sls", "E_inf": 800, "tau": 0.2}},
      "model": "exact"})");
  const Scene f = fitted_scene(s, {estimate(FitParameter::E, 2500), estimate(FitParameter::R, 2e-5),
                                   estimate(FitParameter::E_inf, 900), estimate(FitParameter::tau, 0.4),
                                   estimate(FitParameter::delta0, 1e-6), estimate(FitParameter::P0, 1e-9),
                                   estimate(FitParameter::delta0, 2e-6, 1)});
  CHECK(f.medium.E == 2500);
  REQUIRE(f.medium.relaxation.g.size() == 1);
  CHECK(rel_err(2500 * (1.0 - f.medium.relaxation.g[0]), 900) < 1e-14);  // E_inf absolute
  CHECK(f.medium.relaxation.tau[0] == 0.4);
  CHECK(f.origin.json.find("2e-05") != std::string::npos);
  const Scene md = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "half_space", "E": 1e9, "nu": 0.3}, "w": 0.05, "adhesion": {"model": "maugis_dugdale", "z0": 3e-10}})");
  const Scene g = fitted_scene(md, {estimate(FitParameter::w, 0.01), estimate(FitParameter::sigma0, 5e7)});
  CHECK(g.w == 0.01);
  CHECK(*g.adhesion.sigma0 == 5e7);
  CHECK_FALSE(g.adhesion.z0.has_value());
  CHECK(fitted_scene(f, {}).origin.json == f.origin.json);  // idempotent
}

TEST_CASE("fitted scene: a stack's moduli scale together, E being the top layer's", "[fit][scene]") {
  const Scene s = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-4}, "model": "exact",
      "medium": {"type": "layers", "layers": [{"E": 1e4, "nu": 0.45, "h": 1e-6}, {"E": 4e4, "nu": 0.3, "h": 2e-6}],
                 "base": {"E": 2e5, "nu": 0.3}}})");
  const Scene f = fitted_scene(s, {estimate(FitParameter::E, 3e4)});
  REQUIRE(f.medium.stack.layers.size() == 2);
  CHECK(f.medium.stack.layers[0].E == 3e4);
  CHECK(rel_err(f.medium.stack.layers[1].E, 1.2e5) < 1e-15);
  CHECK(f.origin.json.find("600000") != std::string::npos);  // the elastic base too
}

TEST_CASE("fitted scene: what a scene cannot hold is an InputError naming the parameter", "[fit][scene]") {
  const Scene layer = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-4},
      "medium": {"type": "layer", "E": 1e4, "nu": 0.3, "h": 1e-5}, "model": "two_term"})");
  CHECK_THROWS_WITH(fitted_scene(layer, {estimate(FitParameter::K, 1e9)}), Catch::Contains("K was fitted but"));
  CHECK_THROWS_WITH(fitted_scene(layer, {estimate(FitParameter::E, std::numeric_limits<double>::quiet_NaN())}),
                    Catch::Contains("not finite"));
  Scene code = layer;
  code.origin = SceneOrigin{};
  CHECK_THROWS_WITH(fitted_scene(code, {estimate(FitParameter::E, 1e4)}), Catch::Contains("built in code"));
  const Scene cone = parse_scene(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70},
      "medium": {"type": "half_space", "E": 1e4, "nu": 0.5}, "model": "half_space"})");
  CHECK_THROWS_WITH(fitted_scene(cone, {estimate(FitParameter::R, 1e-5)}), Catch::Contains("no radius R"));
}

TEST_CASE("fitted scene: a fit's scene simulates the curve it was fitted to", "[fit][scene]") {
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "half_space", "E": 2e4, "nu": 0.5}, "model": "half_space", "w": 1e-4})");
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.points_per_branch = 200;
  o.branch = Branch::retract;
  const CurveData c = simulate_curve(truth, o);
  Scene start = truth;
  start.medium.E = 5e4;
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::w};
  f.branch = Branch::retract;
  const FitSummary s = fit(c, start, f);
  REQUIRE(s.converged);
  const Scene back = fitted_scene(start, s.parameters);
  CHECK(rel_err(back.medium.E, 2e4) < 1e-6);
  CHECK(rel_err(back.w, 1e-4) < 1e-6);
  const CurveData again = simulate_curve(back, o);
  REQUIRE(again.P.size() == c.P.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < c.P.size(); ++i) worst = std::max(worst, std::abs(again.P[i] - c.P[i]));
  CHECK(worst < 1e-6 * std::abs(c.P.front()));
}
