// The thin-layer model uniform in nu: its constants against the stiffness expansion, its
// pressure form against an independent Bessel-function evaluation, the incompressible law
// at nu = 1/2, the stiffness identity, and the exact layer over nu in [0, 1/2].
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/bessel.hpp>

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

double worst_difference(const NonAdhesiveState& s, const NonAdhesiveState& reference) {
  return std::max({rel_err(s.P_H, reference.P_H), rel_err(s.delta_H, reference.delta_H),
                   rel_err(s.S, reference.S)});
}
}  // namespace

TEST_CASE("uniform layer: eps = 1/K and D = -G/K^2 of the stiffness expansion - finite at nu = 1/2", "[uniform]") {
  for (double nu : {-0.3, 0.1, 0.3, 0.45, 0.499}) {
    const ElasticLayer layer{2e4, nu, 3e-5, Base::bonded};
    const ThinLayerConstants k = thin_layer_constants(layer);
    const UniformLayerConstants u = uniform_layer_constants(layer);
    INFO("nu = " << nu);
    CHECK(rel_err(u.eps, 1.0 / k.K) < 1e-14);
    CHECK(rel_err(u.D, -k.G / (k.K * k.K)) < 1e-13);
  }
  const ElasticLayer half{2e4, 0.5, 3e-5, Base::bonded};
  CHECK(uniform_layer_constants(half).eps == 0.0);
  CHECK(rel_err(uniform_layer_constants(half).D, std::pow(3e-5, 3) / 2e4) < 1e-15);
}

TEST_CASE("uniform layer: pressure form against unscaled Bessel functions and K (nu = 0.3, 0.45)", "[uniform]") {
  // Oracle: the compressible route P_H = pi K (a^2 delta_H - 2 M), S = pi K a^2 (1 - 2 I1/(x I0))
  // with Boost's I0, I1 and a separate quadrature - algebraically equal, numerically independent.
  boost::math::quadrature::tanh_sinh<double> rule;
  for (double nu : {0.3, 0.45}) {
    const ElasticLayer layer{1.0, nu, 1.0, Base::bonded};
    const UniformLayerConstants c = uniform_layer_constants(layer);
    const double K = 1.0 / c.eps, k = std::sqrt(c.eps / c.D);
    for (const ProfilePtr& p : {make_sphere(40.0), make_cone(1.3)}) {
      const auto model = make_uniform_layer(p, layer, false);
      for (double a : {0.3, 2.0, 9.0}) {
        using boost::math::cyl_bessel_i;
        const double x = k * a;
        const double top = rule.integrate([&](double r) { return p->f(r) * cyl_bessel_i(0, k * r) * r; }, 0.0, a);
        const double delta = top / (a * cyl_bessel_i(1, x) / k);
        const double P = kPi * K * (a * a * delta - 2.0 * p->moment(a));
        const double S = kPi * K * a * a * (1.0 - 2.0 * cyl_bessel_i(1, x) / (x * cyl_bessel_i(0, x)));
        const NonAdhesiveState s = model->state(a);
        INFO(p->describe() << " nu = " << nu << " a = " << a);
        CHECK(rel_err(s.delta_H, delta) < 1e-12);
        CHECK(rel_err(s.P_H, P) < 1e-9);  // the oracle cancels: a^2 delta ~ 2M
        CHECK(rel_err(s.S, S) < 1e-12);
      }
    }
  }
}

TEST_CASE("uniform layer: at nu = 1/2 without edge correction it is the incompressible law", "[uniform]") {
  const ElasticLayer layer{3e4, 0.5, 2e-5, Base::bonded};
  for (const ProfilePtr& p : {make_sphere(1e-3), make_cone(1.2), make_power_law(30.0, 1.5)}) {
    const auto uniform = make_uniform_layer(p, layer, false), lubrication = make_incompressible_layer(p, layer);
    for (double a : {1e-5, 2e-4}) {
      const NonAdhesiveState u = uniform->state(a), l = lubrication->state(a);
      INFO(p->describe() << " a = " << a);
      CHECK(worst_difference(u, l) < 1e-12);
      CHECK(rel_err(u.dS_da, l.dS_da) < 1e-14);
    }
  }
  // And near it (x = k a small but not 0) the series branch joins continuously.
  const auto p = make_paraboloid(1e-3);
  const NonAdhesiveState near = make_uniform_layer(p, {3e4, 0.5 - 1e-12, 2e-5, Base::bonded}, false)->state(1e-4);
  CHECK(worst_difference(near, make_incompressible_layer(p, layer)->state(1e-4)) < 1e-9);
}

TEST_CASE("uniform layer: dP_H/d delta_H = S and S' = dS/da on every branch", "[uniform]") {
  // nu = 0.1: shear form; 0.25 + 1e-6: pressure form with x = k a >> 1 (Winkler-like);
  // 0.3, 0.45, 0.499: pressure form across x ~ 1; -0.3: auxetic, pressure form.
  for (double nu : {-0.3, 0.1, 0.250001, 0.3, 0.45, 0.499}) {
    const ElasticLayer layer{1.0, nu, 1.0, Base::bonded};
    for (const ProfilePtr& p : {make_sphere(50.0), make_cone(1.3),
                                make_table_profile({0.0, 2.0, 4.0, 8.0, 16.0}, {0.0, 0.04, 0.17, 0.7, 3.0})}) {
      const auto model = make_uniform_layer(p, layer);
      for (double a : {1.5, 5.0, 11.0}) {
        // Derivatives in units of a: Boost's finite-difference step is absolute.
        auto along = [&](auto field) {
          return boost::math::differentiation::finite_difference_derivative(
                     [&](double t) { return field(model->state(a * t)); }, 1.0) / a;
        };
        const double dP = along([](const NonAdhesiveState& s) { return s.P_H; });
        const double dd = along([](const NonAdhesiveState& s) { return s.delta_H; });
        const double dS = along([](const NonAdhesiveState& s) { return s.S; });
        const NonAdhesiveState s = model->state(a);
        INFO(p->describe() << " nu = " << nu << " a = " << a);
        CHECK(rel_err(dP / dd, s.S) < 1e-7);
        CHECK(rel_err(s.dS_da, dS) < 1e-7);
      }
    }
  }
}

TEST_CASE("uniform layer: error against the exact layer, uniformly in nu", "[uniform]") {
  // Measured (docs/models.md): uncorrected O(h/a) with coefficient <= 8.6; edge-corrected
  // <= 6 (h/a)^2 for nu <= 0.49, and 0.5 h/a at nu = 1/2 where the edge is not a pure shift.
  for (double nu : {0.0, 0.2, 0.3, 0.45, 0.49, 0.5}) {
    const ElasticLayer layer{1.0, nu, 1.0, Base::bonded};
    for (const ProfilePtr& p : {make_paraboloid(1e3), make_cone(1.4)}) {
      const auto exact = make_exact_layer(p, layer);
      const auto corrected = make_uniform_layer(p, layer), plain = make_uniform_layer(p, layer, false);
      for (double a : {10.0, 30.0}) {
        const NonAdhesiveState e = exact->state(a);
        const double err_plain = worst_difference(plain->state(a), e);
        const double err = worst_difference(corrected->state(a), e);
        INFO(p->describe() << " nu = " << nu << " a/h = " << a << ": " << err_plain << " -> " << err);
        CHECK(err_plain * a < 9.0);
        if (nu < 0.5)
          CHECK(err * a * a < 7.0);
        else
          CHECK(err * a < 0.5);
        CHECK(err < err_plain);
      }
    }
  }
}

TEST_CASE("uniform layer: JKR pull-off of a paraboloid at nu = 1/2 is -3 pi w R", "[uniform]") {
  const double R = 2e-3, w = 0.02;
  const JkrSolution jkr(make_uniform_layer(make_paraboloid(R), {3e4, 0.5, 2e-5, Base::bonded}, false), w);
  const auto po = jkr.pull_off();
  REQUIRE(po);
  CHECK(rel_err(po->P, -3.0 * kPi * w * R) < 1e-8);
}

TEST_CASE("uniform layer: scenes and bad input", "[uniform]") {
  const auto p = make_paraboloid(1.0);
  CHECK_THROWS_WITH(make_uniform_layer(p, {1.0, 0.6, 1.0, Base::bonded}), Catch::Contains("nu = 0.6 ") && Catch::Contains("(-1, 0.5]"));
  CHECK_THROWS_WITH(make_uniform_layer(p, {1.0, 0.3, 1.0, Base::frictionless}), Catch::Contains("bonded"));
  CHECK_THROWS_WITH(make_uniform_layer(p, {1.0, 0.3, 0.0, Base::bonded}), Catch::Contains("h = 0"));
  CHECK_THROWS_WITH(make_uniform_layer(p, {1.0, 0.3, 1.0, Base::bonded})->state(-2.0), Catch::Contains("-2"));
  const Scene ok = parse_scene(R"({"indenter": {"shape": "sphere", "R": 1e-5},
      "medium": {"type": "layer", "E": 1e4, "nu": 0.49, "h": 1e-6}, "model": "uniform", "w": 0.01})");
  const BuiltScene built = build_scene(ok);
  CHECK(built.model->name() == "uniform");
  CHECK(built.resolved.warnings.empty());  // no compressible constants, no non-uniformity warning
  CHECK_THROWS_WITH(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layer", "E": 1e4, "nu": 0.3, "h": 1e-5, "base": "frictionless"}, "model": "uniform"})"),
                    Catch::Contains("bonded"));
}
