// Pyramids: the equivalent cone reproduces the published pyramid force law, a fit of data made
// from that law (not from the library) returns its modulus, and the approximation is stated.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/answer.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/profile.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
constexpr double kDeg = M_PI / 180.0;

std::string pyramid_scene(double deg, int sides, double w = 0.0) {
  return R"({"indenter": {"shape": "pyramid", "semi_angle_deg": )" + std::to_string(deg) +
         R"(, "sides": )" + std::to_string(sides) +
         R"(}, "medium": {"type": "half_space", "E": 2000.0, "nu": 0.5}, "w": )" + std::to_string(w) + "}";
}

bool mentions_pyramid(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings)
    if (w.find("pyramid is modelled by its axisymmetric equivalent cone") != std::string::npos) return true;
  return false;
}
}  // namespace

TEST_CASE("a pyramid's Hertz force is Bilodeau's c_n E* tan(theta) delta^2", "[profile][pyramid]") {
  // Bilodeau (1992): c_4 = 0.7453, c_3 = 0.8887 with theta the face semi-angle.
  for (const auto& [sides, c] : {std::pair{4, 0.7453}, std::pair{3, 0.8887}}) {
    for (double deg : {10.0, 35.0, 70.0}) {
      const Scene scene = parse_scene(pyramid_scene(deg, sides));
      const CurveAnswer answer = solve_curve(scene, {1e-7, 1e-6, 3e-5});
      const double E_star = 2000.0 / (1.0 - 0.25);
      for (const AdhesiveState& s : answer.states) {
        INFO("sides " << sides << ", " << deg << " deg, a = " << s.a);
        const double delta = s.hertz.delta_H;
        CHECK(rel_err(s.hertz.P_H, c * E_star * std::tan(deg * kDeg) * delta * delta) < 1e-12);
      }
      CHECK(mentions_pyramid(answer.warnings));
      CHECK(mentions_pyramid(solve_summary(parse_scene(pyramid_scene(deg, sides, 1e-4))).warnings));
    }
  }
}

TEST_CASE("the equivalent cone is wider than the pyramid's face angle and names it", "[profile][pyramid]") {
  const PyramidEquivalence e = pyramid_equivalent_cone(35.0 * kDeg, 4);
  // tan(beta) = (pi/2) c_4 tan(theta): 1.17071 tan(35 deg) = 0.81975, beta = 39.34295 deg.
  CHECK(std::abs(e.cone_semi_angle_rad / kDeg - 39.342951) < 1e-6);
  CHECK(e.relative_error > 0.0);
  const ProfilePtr p = make_pyramid(35.0 * kDeg, 4);
  CHECK(p->describe().rfind("pyramid(sides=4", 0) == 0);
  REQUIRE(p->approximation().has_value());
  CHECK(p->approximation()->find("5.1 %") != std::string::npos);
  CHECK_FALSE(make_cone(35.0 * kDeg)->approximation().has_value());
  CHECK_THROWS_WITH(make_pyramid(35.0 * kDeg, 5), Catch::Contains("sides") && Catch::Contains("3 or 4"));
  CHECK_THROWS_AS(make_pyramid(M_PI / 2, 4), DomainError);
}

TEST_CASE("bad pyramid scenes name the key, its value and the valid range", "[profile][pyramid][scene]") {
  const auto refused = [](const std::string& indenter) {
    const std::string json = R"({"indenter": )" + indenter + R"(, "medium": {"type": "half_space", "E": 1e3, "nu": 0.5}})";
    try {
      parse_scene(json, "s.json");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CHECK_THAT(refused(R"({"shape": "pyramid", "semi_angle_deg": 35, "sides": 5})"),
             Catch::Contains("indenter.sides") && Catch::Contains("3 or 4"));
  CHECK_THAT(refused(R"({"shape": "pyramid", "semi_angle_deg": 35, "sides": 3.5})"), Catch::Contains("indenter.sides"));
  CHECK_THAT(refused(R"({"shape": "pyramid", "semi_angle_deg": 95, "sides": 4})"),
             Catch::Contains("semi_angle_deg") && Catch::Contains("(0, 90)"));
  CHECK_THAT(refused(R"({"shape": "pyramid", "semi_angle_deg": 35})"), Catch::Contains("sides"));
  CHECK_THAT(refused(R"({"shape": "pyramid", "semi_angle_deg": 35, "sides": 4, "R": 1})"), Catch::Contains("R"));
}

TEST_CASE("a fit with a pyramid returns the modulus of data made from the pyramid law", "[profile][pyramid][fit]") {
  // Approach data from F = 0.7453 E* tan(theta) (delta - delta0)^2 written here, not by the library.
  const double E = 3000.0, nu = 0.5, theta = 35.0 * kDeg, delta0 = 2e-7;
  const double c = 0.7453 * E / (1.0 - nu * nu) * std::tan(theta);
  CurveData curve;
  for (int i = 0; i < 200; ++i) {
    const double delta = 1e-6 * i / 199.0;
    const double d = std::max(delta - delta0, 0.0);
    curve.delta.push_back(delta);
    curve.P.push_back(c * d * d);
    curve.segment.push_back(0);
  }
  const Scene scene = parse_scene(pyramid_scene(35.0, 4));
  FitOptions options;
  options.free = {FitParameter::E, FitParameter::delta0};
  const FitSummary s = fit(curve, scene, options);
  REQUIRE(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, E) < 1e-6);
  CHECK(std::abs(s[FitParameter::delta0].value - delta0) < 1e-12);
  CHECK(mentions_pyramid(s.warnings));
}
