// The adhesive laws and the scene's "adhesion" key (adhesion.hpp): the classical DMT limit
// against its closed form, the JKR law against JkrSolution, and every refusal naming its key.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/scene.hpp"

using namespace layerjkr;
using Catch::Matchers::Contains;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

TEST_CASE("classical DMT on a half-space pulls off at a = 0 with 2 pi w R", "[adhesion]") {
  const double R = 20e-9, E = 2e9, nu = 0.3, w = 0.05;
  const ContactModelPtr hs = make_half_space(make_paraboloid(R), E, nu);
  AdhesionSpec dmt;
  dmt.model = AdhesionModel::dmt;
  const AdhesiveSolution sol(make_adhesive_law(hs, ModelSpec{}, w, dmt));
  const auto po = sol.pull_off();
  REQUIRE(po);
  CHECK(po->a == 0.0);
  CHECK(po->P == Approx(-2.0 * kPi * w * R).epsilon(1e-14));
  CHECK(po->delta == 0.0);
  CHECK_FALSE(sol.fixed_grips_critical());  // delta(a) = a^2/R rises: no instability
  // Off pull-off: P = K a^3 / R - 2 pi w R, delta = a^2 / R (Derjaguin-Muller-Toporov 1975).
  const double E_star = E / (1 - nu * nu), K = 4.0 * E_star / 3.0, a = 3e-9;
  const AdhesiveState s = sol.at(a);
  CHECK(s.P == Approx(K * a * a * a / R - 2.0 * kPi * w * R).epsilon(1e-13));
  CHECK(s.delta == Approx(a * a / R).epsilon(1e-13));
  // The zero-load radius: K a^3 / R = 2 pi w R.
  CHECK(*sol.zero_load_radius() == Approx(std::cbrt(2.0 * kPi * w * R * R / K)).epsilon(1e-12));
  CHECK(summarize(sol).adhesion == AdhesionModel::dmt);
  CHECK_THAT(summarize(sol).model, Contains("dmt"));
}

TEST_CASE("classical DMT on a layer is the layer's non-adhesive state less 2 pi w R", "[adhesion]") {
  const double R = 1e-3, w = 0.1;
  const ElasticLayer layer{1e6, 0.45, 1e-4, Base::bonded};
  const ContactModelPtr exact = make_exact_layer(make_paraboloid(R), layer);
  AdhesionSpec dmt;
  dmt.model = AdhesionModel::dmt;
  const AdhesiveSolution sol(make_adhesive_law(exact, ModelSpec{}, w, dmt));
  for (double a : {2e-5, 1e-4, 4e-4}) {
    const NonAdhesiveState h = exact->state(a);
    const AdhesiveState s = sol.at(a);
    CHECK(s.P == Approx(h.P_H - 2.0 * kPi * w * R).epsilon(1e-14));
    CHECK(s.delta == h.delta_H);
  }
  CHECK(sol.pull_off()->P == Approx(-2.0 * kPi * w * R).epsilon(1e-14));
}

TEST_CASE("the JKR law is the transform JkrSolution always used", "[adhesion]") {
  const ContactModelPtr hs = make_half_space(make_paraboloid(1e-3), 1e6, 0.5);
  const AdhesiveSolution by_law(make_adhesive_law(hs, ModelSpec{}, 0.05, AdhesionSpec{}));
  const JkrSolution by_model(hs, 0.05);
  CHECK(by_law.pull_off()->P == by_model.pull_off()->P);
  // The half-space's JKR pull-off, -3/2 pi w R.
  CHECK(by_model.pull_off()->P == Approx(-1.5 * kPi * 0.05 * 1e-3).epsilon(1e-10));
  CHECK(by_law.law().model() == AdhesionModel::jkr);
}

TEST_CASE("classical DMT refuses a tip without a radius and says what to give", "[adhesion]") {
  const ContactModelPtr cone = make_half_space(make_cone(70.0 * kPi / 180.0), 1e6, 0.5);
  AdhesionSpec dmt;
  dmt.model = AdhesionModel::dmt;
  CHECK_THROWS_WITH(make_adhesive_law(cone, ModelSpec{}, 0.05, dmt),
                    Contains("f''(0) > 0") && Contains("sigma0"));
}

TEST_CASE("the Dugdale stress comes from sigma0, z0 or the assumed spacing", "[adhesion]") {
  AdhesionSpec a;
  CHECK(a.stress_assumed());
  // Lennard-Jones: sigma_max = 16 w / (9 sqrt 3 z0) = 1.0264 w / z0.
  CHECK(a.dugdale_stress(0.1) == Approx(1.02640 * 0.1 / 0.3e-9).epsilon(1e-5));
  a.z0 = 0.5e-9;
  CHECK(a.dugdale_stress(0.1) == Approx(16.0 * 0.1 / (9.0 * std::sqrt(3.0) * 0.5e-9)).epsilon(1e-15));
  a.z0.reset();
  a.sigma0 = 3e7;
  CHECK(a.dugdale_stress(0.1) == 3e7);
  a.z0 = 1e-9;
  CHECK_THROWS_WITH(a.validate(), Contains("z0") && Contains("sigma0"));
}

TEST_CASE("a scene's adhesion key is read and every bad value named", "[adhesion][scene]") {
  const std::string head =
      R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "half_space", "E": 1e9, "nu": 0.3}, "w": 0.05)";
  const Scene s = parse_scene(head + R"(, "adhesion": {"model": "maugis_dugdale", "sigma0": 2e7}})");
  CHECK(s.adhesion.model == AdhesionModel::maugis_dugdale);
  CHECK(*s.adhesion.sigma0 == 2e7);
  CHECK(parse_scene(head + "}").adhesion.model == AdhesionModel::jkr);
  CHECK(*parse_scene(head + R"(, "adhesion": {"z0": 4e-10}})").adhesion.z0 == 4e-10);
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": {"model": "schwarz"}})"),
                    Contains("adhesion.model") && Contains("schwarz") && Contains("maugis_dugdale"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": {"model": "maugis_dugdale"}})"),
                    Contains("sigma0") && Contains("z0"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": {"sigma0": -1}})"),
                    Contains("adhesion.sigma0") && Contains("-1") && Contains("> 0"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": {"sigma0": 1e7, "z0": 3e-10}})"), Contains("both"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": {"range": 1}})"), Contains("adhesion.range"));
  CHECK_THROWS_WITH(parse_scene(head + R"(, "adhesion": "dmt"})"), Contains("adhesion") && Contains("object"));
}
