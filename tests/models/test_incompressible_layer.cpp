// The thin incompressible bonded layer (lubrication law) against its closed forms, the
// stiffness identity, the JKR thin-layer pull-off and the exact layer at nu = 1/2.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
constexpr double kPi = 3.14159265358979323846;
const ElasticLayer kLayer{3e4, 0.5, 2e-5, Base::bonded};
}  // namespace

TEST_CASE("incompressible layer: paraboloid and flat-punch closed forms (theory.md s.2)", "[incompressible]") {
  const double R = 5e-3, E = kLayer.E, h = kLayer.h, mu = E / 3.0;
  const auto model = make_incompressible_layer(make_paraboloid(R), kLayer);
  for (double a : {1e-5, 2e-4, 3e-3}) {
    const NonAdhesiveState s = model->state(a);
    CHECK(rel_err(s.delta_H, a * a / (4.0 * R)) < 1e-14);
    CHECK(rel_err(s.P_H, kPi * mu * std::pow(a, 6) / (32.0 * R * h * h * h)) < 1e-13);
    CHECK(rel_err(s.P_H, 2.0 * kPi * mu * R * R * std::pow(s.delta_H, 3) / (h * h * h)) < 1e-13);
    CHECK(rel_err(s.S, 3.0 * kPi * mu * std::pow(a, 4) / (8.0 * h * h * h)) < 1e-14);
    // In units of a: Boost's finite-difference step is absolute.
    const double slope = boost::math::differentiation::finite_difference_derivative(
                             [&](double x) { return model->state(a * x).S; }, 1.0) / a;
    CHECK(rel_err(s.dS_da, slope) < 1e-9);
  }
}

TEST_CASE("incompressible layer: dP_H = S d delta_H for profiles without closed forms", "[incompressible]") {
  // Oracle: P_H(a) = int_0^a S(s) delta_H'(s) ds, integrated numerically from the model's own
  // S and a finite-difference delta_H' - independent of the closed form for P_H.
  const ProfilePtr profiles[] = {make_sphere(1e-3),
                                 make_table_profile({0.0, 1e-4, 2e-4, 4e-4, 8e-4}, {0.0, 4e-6, 1.7e-5, 7e-5, 3e-4}),
                                 make_power_law(30.0, 1.5)};
  boost::math::quadrature::tanh_sinh<double> rule;
  for (const ProfilePtr& p : profiles) {
    const auto model = make_incompressible_layer(p, kLayer);
    const double a = 3e-4;
    const double integral = rule.integrate(
        [&](double s) {
          const double d = boost::math::differentiation::finite_difference_derivative(
                               [&](double x) { return model->state(s * x).delta_H; }, 1.0) / s;
          return model->state(s).S * d;
        },
        1e-6 * a, a, 1e-10);  // below 1e-6 a the integrand is ~1e-30 of the total
    INFO(p->describe());
    CHECK(rel_err(model->state(a).P_H, integral) < 1e-7);
  }
}

TEST_CASE("incompressible layer: JKR pull-off of a paraboloid is -3 pi w R", "[incompressible]") {
  // theory.md s.5: a thin incompressible bonded layer gives -3 pi w R whatever E and h.
  for (double w : {1e-3, 0.05}) {
    const double R = 2e-3;
    const JkrSolution jkr(make_incompressible_layer(make_paraboloid(R), kLayer), w);
    const auto po = jkr.pull_off();
    REQUIRE(po);
    CHECK(rel_err(po->P, -3.0 * kPi * w * R) < 1e-9);
  }
}

TEST_CASE("incompressible layer: the exact layer at nu = 1/2 approaches it as O(h/a)", "[incompressible]") {
  const auto p = make_paraboloid(1e3);
  const ElasticLayer unit{1.0, 0.5, 1.0, Base::bonded};
  const auto thin = make_incompressible_layer(p, unit), exact = make_exact_layer(p, unit);
  double previous = INFINITY;
  for (double a : {30.0, 100.0, 300.0}) {
    const NonAdhesiveState t = thin->state(a), e = exact->state(a);
    const double err = std::max({rel_err(t.P_H, e.P_H), rel_err(t.delta_H, e.delta_H), rel_err(t.S, e.S)});
    INFO("a/h = " << a << " worst relative difference " << err);
    CHECK(err * a < 10.0);     // O(h/a) with a measured constant of 8-9
    CHECK(err < previous / 2.5);  // falling like h/a (3.3x per step in the limit)
    previous = err;
  }
}

TEST_CASE("incompressible layer: bad input names the parameter", "[incompressible]") {
  const auto p = make_paraboloid(1.0);
  CHECK_THROWS_WITH(make_incompressible_layer(p, {1.0, 0.49, 1.0, Base::bonded}), Catch::Contains("nu = 0.49"));
  CHECK_THROWS_WITH(make_incompressible_layer(p, {1.0, 0.5, 1.0, Base::frictionless}), Catch::Contains("bonded"));
  CHECK_THROWS_WITH(make_incompressible_layer(p, {1.0, 0.5, -1.0, Base::bonded}), Catch::Contains("h = -1"));
  CHECK_THROWS_WITH(make_incompressible_layer(p, {1.0, 0.5, 1.0, Base::bonded})->state(-1.0), Catch::Contains("-1"));
  CHECK_THROWS_WITH(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layer", "E": 1e4, "nu": 0.3, "h": 1e-5}, "model": "incompressible"})"),
                    Catch::Contains("nu = 0.") && Catch::Contains("0.5 exactly"));
  const Scene ok = parse_scene(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70},
      "medium": {"type": "layer", "E": 1e4, "nu": 0.5, "h": 1e-5}, "model": "incompressible"})");
  CHECK(build_scene(ok).model->name() == "incompressible");
}
