// The adhesive laws and the scene's "adhesion" key (adhesion.hpp): the classical DMT limit
// against its closed form, the JKR law against JkrSolution, and every refusal naming its key.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/answer.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/maugis_dugdale.hpp"
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

namespace {
Scene md_scene(const std::string& indenter, const std::string& medium, const std::string& model, double w,
               const std::string& adhesion) {
  return parse_scene(R"({"indenter": )" + indenter + R"(, "medium": )" + medium + R"(, "model": ")" + model +
                     R"(", "w": )" + std::to_string(w) + R"(, "adhesion": )" + adhesion + "}");
}
AdhesiveSolution solution_of(const Scene& s) {
  const BuiltScene b = build_scene(s, 0.0, false);
  return AdhesiveSolution(make_adhesive_law(b.model, b.resolved.spec, s.w, s.adhesion));
}
const std::string kHalfSpace = R"({"type": "half_space", "E": 1e9, "nu": 0.4})";
}  // namespace

TEST_CASE("a Maugis-Dugdale scene on a half-space pulls off where Maugis' closed form does", "[adhesion]") {
  const double R = 2e-8, w = 0.05, sigma0 = 5e7, E_star = 1e9 / (1 - 0.16);
  const Scene s = md_scene(R"({"shape": "paraboloid", "R": 2e-8})", kHalfSpace, "half_space", w,
                           R"({"model": "maugis_dugdale", "sigma0": 5e7})");
  const AdhesiveSolution sol = solution_of(s);
  const CriticalPoint ref = maugis_dugdale_pull_off(R, E_star, w, sigma0);
  CHECK(sol.pull_off()->P == Approx(ref.P).epsilon(1e-12));
  CHECK(sol.pull_off()->a == Approx(ref.a).epsilon(1e-6));
  CHECK(sol.at(ref.a).c > ref.a);
  CHECK(sol.law().model() == AdhesionModel::maugis_dugdale);
  // The general solver on the same half-space (a sphere of the same tip radius is a different
  // profile, so compare a paraboloid by the Dugdale law's own path through DMT below).
  const SummaryAnswer answer = solve_summary(s);
  CHECK(answer.contact.adhesion == AdhesionModel::maugis_dugdale);
  CHECK(answer.contact.pull_off->P == Approx(ref.P).epsilon(1e-12));
  REQUIRE(answer.adhesion);
  CHECK(answer.adhesion->pull_off_error == 0.0);
}

TEST_CASE("Maugis-Dugdale of a cone on a half-space tends to the cone's JKR pull-off as lambda grows", "[adhesion]") {
  const std::string cone = R"({"shape": "cone", "semi_angle_deg": 70})";
  const double w = 0.05;
  const JkrSolution jkr(build_scene(md_scene(cone, kHalfSpace, "half_space", w, "{}"), 0.0, false).model, w);
  double previous = 1.0;
  for (const double sigma0 : {1e8, 1e9, 1e10}) {
    const std::string adhesion = R"({"model": "maugis_dugdale", "sigma0": )" + std::to_string(sigma0) + "}";
    const double P = solution_of(md_scene(cone, kHalfSpace, "half_space", w, adhesion)).pull_off()->P;
    const double gap = std::abs(P / jkr.pull_off()->P - 1.0);
    CHECK(gap < previous);  // closes as sigma0 (lambda) grows
    previous = gap;
  }
  CHECK(previous < 1e-3);
}

TEST_CASE("Maugis-Dugdale on a layer lies between JKR and DMT and its curve answer is finite", "[adhesion]") {
  const std::string film = R"({"type": "layer", "E": 1e9, "nu": 0.4, "h": 1e-8, "base": "bonded"})";
  const std::string tip = R"({"shape": "paraboloid", "R": 2e-8})";
  const Scene md = md_scene(tip, film, "exact", 0.05, R"({"model": "maugis_dugdale", "z0": 3e-10})");
  const double P_md = solve_summary(md).contact.pull_off->P;
  const double P_jkr = solve_summary(md_scene(tip, film, "exact", 0.05, "{}")).contact.pull_off->P;
  const double P_dmt = -2.0 * kPi * 0.05 * 2e-8;
  CHECK(P_md < P_jkr);
  CHECK(P_md > P_dmt);
  const CurveAnswer c = solve_curve(md, {1e-9, 5e-9, 1e-8});
  for (const AdhesiveState& s : c.states) {
    CHECK(s.c > s.a);
    CHECK(std::isfinite(s.hertz.P_H));
    CHECK(std::isfinite(s.hertz.S));
  }
}

TEST_CASE("DMT with a Dugdale stress tends to the classical 2 pi w R as sigma0 falls", "[adhesion]") {
  const std::string tip = R"({"shape": "paraboloid", "R": 2e-8})";
  double previous = 1.0;
  for (const double sigma0 : {1e8, 1e7, 1e6}) {
    const std::string adhesion = R"({"model": "dmt", "sigma0": )" + std::to_string(sigma0) + "}";
    const AdhesiveSolution sol = solution_of(md_scene(tip, kHalfSpace, "half_space", 0.05, adhesion));
    const double gap = std::abs(sol.pull_off()->P / (-2.0 * kPi * 0.05 * 2e-8) - 1.0);
    CHECK(gap < previous);
    previous = gap;
  }
  CHECK(previous < 1e-2);
}

TEST_CASE("the Dugdale laws refuse a model without the gap outside the contact", "[adhesion]") {
  const std::string film = R"({"type": "layer", "E": 1e6, "nu": 0.3, "h": 1e-4, "base": "bonded"})";
  const Scene s = md_scene(R"({"shape": "paraboloid", "R": 1e-2})", film, "two_term", 0.05,
                           R"({"model": "maugis_dugdale", "sigma0": 1e6})");
  CHECK_THROWS_WITH(solve_summary(s), Contains("maugis_dugdale") && Contains("exact") && Contains("two_term"));
}
