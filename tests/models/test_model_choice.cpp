// Model error estimates and model "auto": the estimate bounds the error against a finer
// exact solution (an independent discretisation, no tables), for any profile; auto picks
// the cheapest model within tolerance. The 200-scene validation is tools/auto_validation.cpp
// (docs/data/auto_validation.md); here a dozen seeded random scenes keep it honest in CI.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model_choice.hpp"
#include "layerjkr/model_error.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

// A finer exact layer than the default: 24 nodes on 2h panels, every radius solved.
ContactModelPtr fine_exact(const ProfilePtr& p, const ElasticLayer& layer) {
  ExactLayerOptions o;
  o.points_per_panel = 24;
  o.panel_width = 2.0;
  o.tabulate_power_laws = false;
  o.estimate_error = false;
  return make_exact_layer(p, layer, o);
}

double true_state_error(const ContactModelPtr& m, const ContactModelPtr& truth, double w, double a) {
  const AdhesiveState s = jkr_transform(m->state(a), w), t = jkr_transform(truth->state(a), w);
  const double force = std::abs(s.P - t.P) / (std::abs(t.hertz.P_H) + std::abs(t.P - t.hertz.P_H));
  const double approach = std::abs(s.delta - t.delta) / (std::abs(t.hertz.delta_H) + std::abs(t.delta - t.hertz.delta_H));
  return std::max(force, approach);
}

}  // namespace

TEST_CASE("state estimates bound the error against a finer exact layer, for any profile", "[auto]") {
  const ElasticLayer layer{1.0, 0.3, 1.0, Base::bonded};
  const double w = 0.02;
  for (const ProfilePtr& p : {make_paraboloid(100.0), make_sphere(80.0), make_cone(1.3), make_power_law(1e-3, 3.0),
                              make_table_profile({0, 4, 8, 16, 32}, {0, 0.1, 0.4, 1.7, 7.0})}) {
    const ContactModelPtr exact = layer_reference(p, layer), truth = fine_exact(p, layer);
    for (ModelKind kind : layer_model_candidates(layer)) {
      const ContactModelPtr m = make_contact_model(p, layer_model_spec(kind, layer));
      const ModelErrorEstimator estimator(m, exact, w);
      for (double a : {2.0, 7.0, 20.0}) {
        const double estimate = estimator.at(a), actual = true_state_error(m, truth, w, a);
        INFO(p->describe() << " " << to_string(kind) << " a/h = " << a << " estimate " << estimate << " actual " << actual);
        CHECK(actual <= estimate);
        CHECK(estimate <= actual * (1 + 1e-6) + 1e-7);  // not vacuous: it is the error
      }
    }
  }
}

TEST_CASE("the exact layer's own estimate bounds its error - models exact for their medium estimate ~0", "[auto]") {
  const ElasticLayer layer{1.0, 0.45, 1.0, Base::bonded};
  const ProfilePtr p = make_sphere(50.0);
  const ContactModelPtr exact = layer_reference(p, layer), truth = fine_exact(p, layer);
  const ModelErrorEstimator own(exact, nullptr, 0.0);
  for (double a : {1.0, 10.0, 40.0}) {
    const double actual = rel_err(exact->state(a).P_H, truth->state(a).P_H);
    INFO("a/h = " << a << " actual " << actual << " estimate " << own.at(a));
    CHECK(actual <= own.at(a));
    CHECK(own.at(a) < 1e-6);
  }
  CHECK(ModelErrorEstimator(make_winkler(p, 1e3), nullptr, 0.1).at(3.0) == 1e-12);
}

TEST_CASE("curve estimates: anchors bracket every radius - beyond 1000 h the error falls as h/a", "[auto]") {
  const ElasticLayer layer{1.0, 0.3, 1.0, Base::bonded};
  const ProfilePtr p = make_paraboloid(1e3);
  const ModelErrorEstimator e(make_winkler(p, thin_layer_constants(layer).K), layer_reference(p, layer), 0.05);
  std::vector<double> radii;
  for (int i = 1; i <= 100; ++i) radii.push_back(0.5 * i);
  const std::vector<double> along = e.along(radii);
  for (std::size_t i = 0; i < radii.size(); i += 7) CHECK(along[i] >= e.at(radii[i]) * (1 - 1e-12));
  CHECK(along.back() == Approx(e.at(50.0)).epsilon(1e-12));
  CHECK(e.at(4000.0) == Approx((e.at(1000.0) - 2e-12) / 4 + 2e-12).epsilon(1e-3));
}

TEST_CASE("summary estimates: the two-term sphere scene is 10-25 % off at a/h = 1.8", "[auto]") {
  // data/scenes/sphere_pdms_film_two_term.json: the README's trade table says 9-21 % in the
  // pull-off force at this a/h; the estimate must say so.
  const Scene s = load_scene(std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/sphere_pdms_film_two_term.json");
  const BuiltScene b = build_scene_for_summary(s);
  const ContactSummary summary = summarize(JkrSolution(b.model, s.w));
  const SummaryError e = error_estimator(s, b).summary(summary);
  CHECK(e.reference == "exact");
  CHECK(e.pull_off_force > 0.05);
  CHECK(e.pull_off_force < 0.3);
  const ContactSummary exact = summarize(JkrSolution(fine_exact(s.profile, {s.medium.E, s.medium.nu, s.medium.h, s.medium.base}), s.w));
  CHECK(rel_err(summary.pull_off->P, exact.pull_off->P) <= e.pull_off_force);
  CHECK(rel_err(*summary.zero_load_radius, *exact.zero_load_radius) <= e.zero_load_radius);
}

TEST_CASE("auto: a cone on a nu = 0.3 layer at a/h = 20 within 1 % is not the exact layer", "[auto]") {
  const ElasticLayer layer{1.0, 0.3, 1.0, Base::bonded};
  const ProfilePtr cone = make_cone(1.3);
  const ModelChoice c = choose_layer_model(cone, layer, 0.0, 0.01, {20.0});
  CHECK(c.model != ModelKind::exact);
  const double actual = true_state_error(c.contact_model, fine_exact(cone, layer), 0.0, 20.0);
  INFO(to_string(c.model) << " estimate " << c.estimated_error << " actual " << actual);
  CHECK(actual <= c.estimated_error);
  CHECK(c.estimated_error <= 0.01);
  CHECK(c.estimated_error <= actual * (1 + 1e-6) + 1e-8);
}

TEST_CASE("auto: a nu = 0.49 hydrogel gets the uniform model where it is within 1 %, exact elsewhere", "[auto]") {
  const ElasticLayer layer{1e4, 0.49, 1e-6, Base::bonded};
  const ProfilePtr sphere = make_sphere(1e-3);
  const ModelChoice thin = choose_layer_model(sphere, layer, 0.01, 0.01, {100e-6});
  CHECK(thin.model == ModelKind::uniform);
  CHECK(thin.estimated_error < 0.01);
  const ModelChoice thick = choose_layer_model(sphere, layer, 0.01, 0.01, {2e-6});
  CHECK(thick.model == ModelKind::exact);
  CHECK(thick.estimated_error < 1e-6);
}

TEST_CASE("auto on seeded random scenes: the estimate bounds the error, the choice is the cheapest within it", "[auto]") {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int scene = 0; scene < 12; ++scene) {
    const double nu = scene % 4 == 3 ? 0.5 : 0.49 * unit(rng);
    const ElasticLayer layer{1.0, nu, 1.0, scene % 5 == 4 && nu < 0.5 ? Base::frictionless : Base::bonded};
    const double a = std::exp(std::log(2.0) + unit(rng) * std::log(30.0));  // a/h in [2, 60]
    const ProfilePtr p = scene % 3 == 0 ? make_sphere(a * (5 + 20 * unit(rng)))
                         : scene % 3 == 1 ? make_cone(1.0 + 0.5 * unit(rng))
                                          : make_power_law(1e-3, 1.5 + 2.5 * unit(rng));
    const double w = scene % 2 ? 0.0 : 0.01 * unit(rng), tolerance = scene % 2 ? 0.01 : 0.05;
    const ModelChoice c = choose_layer_model(p, layer, w, tolerance, {a});
    const ContactModelPtr truth = fine_exact(p, layer);
    INFO(p->describe() << " nu = " << nu << " a/h = " << a << " w = " << w << " chose " << to_string(c.model));
    CHECK(true_state_error(c.contact_model, truth, w, a) <= std::max(c.estimated_error, 1e-7));
    for (ModelKind kind : layer_model_candidates(layer)) {  // nothing cheaper passes
      if (kind == c.model) break;
      const ContactModelPtr m = make_contact_model(p, layer_model_spec(kind, layer));
      INFO("cheaper " << to_string(kind));
      CHECK(true_state_error(m, truth, w, a) > tolerance);
    }
  }
}

TEST_CASE("auto: scenes need a tolerance and a radius - bad input names the parameter", "[auto][scene]") {
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
  REQUIRE(far.choice);
  CHECK(far.choice->model == ModelKind::winkler);
  CHECK(far.choice->estimated_error <= 0.05);
  CHECK(far.choice->tolerance == 0.05);
  CHECK(far.reference->name() == "exact");
  const auto p = make_paraboloid(1.0);
  const ElasticLayer layer{1.0, 0.3, 1.0, Base::bonded};
  CHECK_THROWS_WITH(choose_layer_model(p, layer, 0.0, 0.0, {1.0}), Catch::Contains("tolerance = 0"));
  CHECK_THROWS_WITH(choose_layer_model(p, layer, 0.0, 0.1, {}), Catch::Contains("radii"));
  CHECK_THROWS_WITH(choose_layer_model(p, layer, -1.0, 0.1, {1.0}), Catch::Contains("w = -1"));
  CHECK_THROWS_WITH(choose_layer_model(p, layer, 0.0, 0.1, {-2.0}), Catch::Contains("-2"));
}

TEST_CASE("every medium's model has a reference or is exact for it", "[auto][scene]") {
  auto built = [](const std::string& medium, const std::string& model) {
    return build_scene(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 0.01}, "medium": )" + medium +
                                   R"(, "model": ")" + model + R"("})"));
  };
  const std::string layer = R"({"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4})";
  for (const char* m : {"leading", "two_term", "edge_corrected", "uniform"}) CHECK(built(layer, m).reference->name() == "exact");
  CHECK_FALSE(built(layer, "exact").reference);
  CHECK(built(R"({"type": "pasternak", "K": 1e9, "G": 10})", "asymptotic").reference->name() == "full_foundation");
  CHECK_FALSE(built(R"({"type": "pasternak", "K": 1e9, "G": 10})", "full").reference);
  CHECK_FALSE(built(R"({"type": "winkler", "K": 1e9})", "winkler").reference);
}
