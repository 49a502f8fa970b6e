// Pyramids: the equivalent cone reproduces the published pyramid force law, a fit of data made
// from that law (not from the library) returns its modulus, and the approximation is stated.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
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
      // The cone equivalence is a stated model error, not a sign of trouble: a notice.
      CHECK(mentions_pyramid(answer.notices));
      CHECK_FALSE(mentions_pyramid(answer.warnings));
      const SummaryAnswer summary = solve_summary(parse_scene(pyramid_scene(deg, sides, 1e-4)));
      CHECK(mentions_pyramid(summary.notices));
      CHECK(summary.warnings.empty());
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
  CHECK(mentions_pyramid(s.notices));
  INFO(s.brief_report());
  CHECK(s.warnings.empty());  // a clean curve of the model's own law: nothing to warn about
}

TEST_CASE("an approach curve fits with a ratio-of-variances point, a pyramid and an indentation range",
          "[profile][pyramid][fit][contact_point]") {
  // Data from Bilodeau's law, with a baseline offset, noise and a stiffer tail beyond 600 nm that
  // the range keeps out: the modulus of the first 500 nm is recovered within its error bars.
  const double E = 2000.0, nu = 0.5, theta = 35.0 * kDeg, delta0 = 1.5e-6, P0 = 3e-11, noise = 2e-12;
  const double c = 0.7453 * E / (1.0 - nu * nu) * std::tan(theta);
  CurveData curve;
  std::uint64_t state = 12345;
  const auto gauss = [&] {  // Box-Muller on a 64-bit LCG: self-contained and repeatable
    const auto uniform = [&] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return (static_cast<double>(state >> 11) + 0.5) / 9007199254740992.0;
    };
    const double u = uniform(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * M_PI * v);
  };
  for (int i = 0; i < 1000; ++i) {
    const double delta = 3e-6 * i / 999.0, d = std::max(delta - delta0, 0.0);
    const double tail = d > 6e-7 ? 4.0 * c * (d - 6e-7) * (d - 6e-7) : 0.0;
    curve.delta.push_back(delta);
    curve.P.push_back(P0 + c * d * d + tail + noise * gauss());
    curve.segment.push_back(0);
  }
  const Scene scene = parse_scene(pyramid_scene(35.0, 4));
  FitOptions options;
  options.free = {FitParameter::E};
  options.contact_point = ContactPointMethod::rov;
  options.indentation_range = Interval{0.0, 5e-7};
  const FitSummary s = fit(curve, scene, options);
  INFO(s.brief_report());
  REQUIRE(s.converged);
  CHECK(s.contact_point.method == ContactPointMethod::rov);
  CHECK(std::abs(s.contact_point.value - delta0) < 4.0 * s.contact_point.standard_error + 2 * 3e-6 / 999.0);
  CHECK(s.contact_point.samples_in_range < s.contact_point.approach_samples);
  // With the found point and baseline fixed, E is the linear least-squares fit of
  // P - P0 = c (delta - delta_c)^2 over the range's samples, written here independently.
  double num = 0.0, den = 0.0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const double d = curve.delta[i] - s.contact_point.value;
    if (d < 0.0 || d > 5e-7) continue;
    num += (curve.P[i] - s.contact_point.baseline) * d * d;
    den += d * d * d * d;
    ++kept;
  }
  CHECK(kept == s.contact_point.samples_in_range);
  const double E_linear = num / den / (0.7453 * std::tan(theta) / (1.0 - nu * nu));
  CHECK(rel_err(s[FitParameter::E].value, E_linear) < 1e-6);
  // rov's point is late by about one of its uncertainties here, which stiffens E; freeing delta0
  // (rov's point is then its start and the range's reference) recovers the true modulus.
  options.free = {FitParameter::E, FitParameter::delta0};
  const FitSummary refined = fit(curve, scene, options);
  INFO(refined.brief_report());
  REQUIRE(refined.converged);
  const ParameterEstimate& e = refined[FitParameter::E];
  CHECK(std::abs(e.value - E) < 4.0 * e.standard_error);
  CHECK(std::abs(refined[FitParameter::delta0].value - delta0) < 4.0 * refined[FitParameter::delta0].standard_error);
  CHECK(mentions_pyramid(s.notices));
  // The report says that the rov point and the model's delta0 differ, and which E comes from.
  const auto says_apart = [](const FitSummary& f) {
    return std::any_of(f.notices.begin(), f.notices.end(), [](const std::string& n) {
      return n.find("the contact point (rov)") != std::string::npos && n.find("fitted delta0") != std::string::npos;
    });
  };
  CHECK(says_apart(refined));
  CHECK_FALSE(says_apart(s));  // delta0 fixed at the rov point: one contact point
  CHECK(refined.brief_report().find("note: the contact point (rov)") != std::string::npos);
}
