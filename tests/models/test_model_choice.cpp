// Model "auto": the error estimates bound the real error off the measured grid, and the
// choice is the cheapest model within tolerance.
#include <catch2/catch.hpp>

#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_choice.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

TEST_CASE("estimated errors bound the measured error at off-grid nu and a/h", "[auto]") {
  const auto p = make_paraboloid(100.0);
  for (Base base : {Base::bonded, Base::frictionless}) {
    for (double nu : {0.05, 0.15, 0.22, 0.27, 0.35, 0.42, 0.47}) {
      const ElasticLayer layer{1.0, nu, 1.0, base};
      ExactLayerOptions o;
      o.max_a_over_h = 40;
      o.estimate_error = false;
      const ExactLayerKernel exact(layer, o);
      const ThinLayerConstants c = thin_layer_constants(layer);
      const auto edge = make_edge_corrected(p, layer);
      for (double r : {0.7, 3.0, 7.0, 15.0, 35.0}) {
        const HertzState e = exact.solve(*p, r).state;
        struct M { const char* name; ContactModelPtr model; };
        std::vector<M> models{{"winkler", make_winkler(p, c.K)}, {"two_term", make_two_term(p, c.K, c.G)}};
        if (r >= 1.0) models.push_back({"edge_corrected", edge});  // a + beta h > 0 needs a/h > 0.5
        if (c.G > 0) models.push_back({"full_foundation", make_full_foundation(p, c.K, c.G)});
        for (const auto& m : models) {
          const HertzState s = m.model->state(r);
          const double actual = std::max(std::abs(s.P_H / e.P_H - 1), std::abs(s.delta_H / e.delta_H - 1));
          const double estimate = estimated_model_error(m.name, layer, r);
          INFO(m.name << " nu=" << nu << " bonded=" << (base == Base::bonded) << " a/h=" << r
                      << " actual=" << actual << " estimate=" << estimate);
          CHECK(actual <= estimate);
          CHECK(estimate < 25 * actual + 0.02);  // conservative, not vacuous
          if (m.name == std::string("edge_corrected")) CHECK(estimate < 25 * actual + 0.05);
        }
      }
    }
  }
}

TEST_CASE("the paraboloid table is not trusted for other profiles", "[auto]") {
  // Measured: with f = B r^4 Winkler's error at a/h = 1 exceeds the paraboloid estimate
  // (0.586 vs 0.509 at nu = 0), so auto must not use it for such profiles.
  const ElasticLayer layer{1.0, 0.0, 1.0, Base::bonded};
  const auto quartic = make_power_law(1e-4, 4.0);
  ExactLayerOptions o;
  o.max_a_over_h = 2;
  o.estimate_error = false;
  const HertzState e = ExactLayerKernel(layer, o).solve(*quartic, 1.0).state;
  const HertzState w = make_winkler(quartic, thin_layer_constants(layer).K)->state(1.0);
  CHECK(std::abs(w.P_H / e.P_H - 1) > estimated_model_error("winkler", layer, 1.0));
  CHECK(choose_layer_model(quartic, layer, 0.9, 1.0).model == "exact");
  CHECK(choose_layer_model(make_cone(1.2), layer, 0.9, 50.0).model == "exact");
  CHECK(choose_layer_model(make_sphere(1e3), layer, 0.9, 50.0).model == "exact");
  CHECK(choose_layer_model(make_power_law(1.0 / 200, 2.0), layer, 0.9, 50.0).model == "winkler");
}

TEST_CASE("estimates beyond the measured domain are infinite", "[auto]") {
  const ElasticLayer bonded{1.0, 0.3, 1.0, Base::bonded};
  CHECK(std::isinf(estimated_model_error("winkler", bonded, 0.3)));  // a/h < 0.5
  CHECK(std::isinf(estimated_model_error("winkler", {1.0, 0.495, 1.0, Base::bonded}, 10.0)));
  CHECK(std::isinf(estimated_model_error("winkler", {1.0, -0.2, 1.0, Base::bonded}, 10.0)));
  CHECK(std::isinf(estimated_model_error("full_foundation", bonded, 10.0)));  // G < 0
  // Beyond a/h = 100 the O(h/a) law scales the last measurement.
  CHECK(estimated_model_error("winkler", bonded, 1000.0) ==
        Approx(estimated_model_error("winkler", bonded, 100.0) / 10));
  CHECK_THROWS_AS(estimated_model_error("hertz", bonded, 10.0), DomainError);
  CHECK_THROWS_AS(estimated_model_error("winkler", bonded, -1.0), DomainError);
}

TEST_CASE("choose_layer_model picks the cheapest model within tolerance", "[auto]") {
  const auto p = make_paraboloid(100.0);
  const ElasticLayer nu03{1.0, 0.3, 1.0, Base::bonded}, nu02{1.0, 0.2, 1.0, Base::bonded};
  CHECK(choose_layer_model(p, nu03, 0.05, 50.0).model == "winkler");
  CHECK(choose_layer_model(p, nu03, 0.01, 20.0).model == "edge_corrected");
  CHECK(choose_layer_model(p, nu03, 0.05, 1.0).model == "exact");
  CHECK(choose_layer_model(p, nu02, 0.03, 10.0).model == "edge_corrected");
  CHECK(choose_layer_model(p, nu02, 0.1, 0.5).model == "full_foundation");  // edge: 19 % in delta
  CHECK(choose_layer_model(p, nu02, 0.2, 10.0).model == "winkler");
  CHECK(choose_layer_model(p, {1.0, 0.5, 1.0, Base::bonded}, 0.5, 50.0).model == "exact");
  const ModelChoice c = choose_layer_model(p, nu03, 0.05, 50.0);
  CHECK(c.estimated_error <= 0.05);
  CHECK(c.reference_radius == 50.0);
  CHECK(c.contact_model->name() == "winkler");
  CHECK_THROWS_WITH(choose_layer_model(p, nu03, 0.0, 1.0), Catch::Contains("tolerance = 0"));
  CHECK_THROWS_WITH(choose_layer_model(p, nu03, 0.1, 0.0), Catch::Contains("a_min = 0"));
}

TEST_CASE("scenes with model auto need a tolerance and a radius of interest", "[auto][scene]") {
  const std::string head = R"({"indenter": {"shape": "paraboloid", "R": 0.01},
      "medium": {"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4}, "model": "auto")";
  CHECK_THROWS_WITH(parse_scene(head + "}"), Catch::Contains("tolerance is missing"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "tolerance": 1.5})"), Catch::Contains("tolerance = 1.5"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "tolerance": "tight"})"), Catch::Contains("tolerance must be a number"));
  CHECK_THROWS_WITH(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 0.01},
      "medium": {"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4}, "model": "leading", "tolerance": 0.1})"),
                    Catch::Contains("tolerance is only used with model \"auto\""));
  const Scene s = parse_scene(head + R"(, "tolerance": 0.05, "w": 0.05})");
  CHECK_THROWS_WITH(build_scene(s), Catch::Contains("a_min"));
  const BuiltScene far = build_scene(s, 5e-3);  // a/h = 50
  CHECK(far.automatic);
  CHECK(far.chosen_model == "winkler");
  CHECK(far.estimated_error <= 0.05);
  CHECK(build_scene(s, summary_reference_radius(s)).chosen_model == "exact");
}
