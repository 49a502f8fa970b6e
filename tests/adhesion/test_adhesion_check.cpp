// The check on every adhesive answer (adhesion_check.hpp): lambda from the contact's own
// compliance against Maugis' definition, the pull-off error against Maugis' closed form, and
// the warnings the answers give - an AFM tip on a stiff film must say JKR is off, and by how much.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/adhesion_check.hpp"
#include "layerjkr/answer.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "layerjkr/scene.hpp"

using namespace layerjkr;
using Catch::Matchers::Contains;

namespace {
std::string scene_text(const std::string& indenter, const std::string& medium, double w, const std::string& extra = "") {
  return R"({"indenter": )" + indenter + R"(, "medium": )" + medium + R"(, "w": )" + std::to_string(w) + extra + "}";
}
const std::string kTip = R"({"shape": "paraboloid", "R": 2e-8})";
}  // namespace

TEST_CASE("lambda from the contact's compliance is Maugis' lambda on a half-space", "[adhesion]") {
  for (const double R : {1e-8, 1e-3})
    for (const double E : {1e6, 1e10})
      for (const double sigma0 : {1e6, 3e8}) {
        const double nu = 0.3, w = 0.07, E_star = E / (1 - nu * nu);
        const JkrSolution jkr(make_half_space(make_paraboloid(R), E, nu), w);
        const NonAdhesiveState at = jkr.model().state(jkr.pull_off()->a);
        CHECK(contact_lambda(at, w, sigma0) == Approx(maugis_lambda(R, E_star, w, sigma0)).epsilon(1e-9));
      }
}

TEST_CASE("a JKR answer on a half-space is judged by Maugis' closed form", "[adhesion]") {
  const double R = 2e-8, E = 2e9, nu = 0.3, w = 0.05, sigma0 = 1e8;
  const SummaryAnswer s = solve_summary(parse_scene(scene_text(
      kTip, R"({"type": "half_space", "E": 2e9, "nu": 0.3})", w, R"(, "adhesion": {"sigma0": 1e8})")));
  REQUIRE(s.adhesion);
  const double lambda = maugis_lambda(R, E / (1 - nu * nu), w, sigma0);
  CHECK(s.adhesion->lambda == Approx(lambda).epsilon(1e-9));
  CHECK(s.adhesion->basis == "closed form");
  CHECK_FALSE(s.adhesion->sigma0_assumed);
  // The JKR pull-off is -3/2 pi w R; Maugis-Dugdale's is maugis_pull_off(lambda) pi w R.
  CHECK(s.adhesion->pull_off_error == Approx(std::abs(-1.5 / maugis_pull_off(lambda).P - 1.0)).epsilon(1e-9));
}

TEST_CASE("a soft large sphere passes the check and an AFM tip on a stiff film does not", "[adhesion]") {
  const SummaryAnswer soft = solve_summary(parse_scene(
      scene_text(R"({"shape": "paraboloid", "R": 1e-3})", R"({"type": "half_space", "E": 1e6, "nu": 0.5})", 0.05)));
  REQUIRE(soft.adhesion);
  CHECK(soft.adhesion->sigma0_assumed);
  CHECK(soft.adhesion->lambda > 100.0);
  CHECK(soft.adhesion->pull_off_error < 0.01);
  for (const std::string& line : soft.warnings) CHECK_THAT(line, !Contains("outside its range"));

  // A 20 nm tip on a 3 GPa polymer film 10 nm thick on silicon (rigid): stiffer than the film's
  // half-space, so lambda is lower still.
  const std::string film = R"({"type": "layer", "E": 3e9, "nu": 0.4, "h": 1e-8, "base": "bonded"})";
  const SummaryAnswer stiff = solve_summary(parse_scene(scene_text(kTip, film, 0.05, R"(, "model": "exact")")));
  const SummaryAnswer bulk = solve_summary(
      parse_scene(scene_text(kTip, R"({"type": "half_space", "E": 3e9, "nu": 0.4})", 0.05)));
  REQUIRE(stiff.adhesion);
  REQUIRE(bulk.adhesion);
  CHECK(stiff.adhesion->lambda < bulk.adhesion->lambda);
  CHECK(stiff.adhesion->pull_off_error > 0.05);
  // Above 1 % the estimate is replaced by Maugis-Dugdale solved on the layer: the estimate
  // (the half-space's at this lambda) bounds it from above.
  CHECK(stiff.adhesion->basis == "solved on the medium");
  CHECK(stiff.adhesion->pull_off_error < std::abs(-1.5 / maugis_pull_off_force(stiff.adhesion->lambda) - 1.0));
  // The same film under the two-term law (not exact for its medium) keeps the estimate.
  const SummaryAnswer law = solve_summary(parse_scene(scene_text(kTip, film, 0.05, R"(, "model": "leading")")));
  REQUIRE(law.adhesion);
  CHECK(law.adhesion->basis == "half-space estimate");
  bool warned = false;
  for (const std::string& line : stiff.warnings)
    if (line.find("JKR is outside its range") != std::string::npos) {
      warned = true;
      CHECK_THAT(line, Contains("lambda = ") && Contains("% off Maugis-Dugdale") && Contains("z0 = 0.3 nm assumed"));
    }
  CHECK(warned);
}

TEST_CASE("the check judges DMT answers too and is absent without adhesion", "[adhesion]") {
  const std::string hs = R"({"type": "half_space", "E": 2e9, "nu": 0.3})";
  const SummaryAnswer dmt =
      solve_summary(parse_scene(scene_text(kTip, hs, 0.05, R"(, "adhesion": {"model": "dmt"})")));
  REQUIRE(dmt.adhesion);
  CHECK(dmt.adhesion->model == AdhesionModel::dmt);
  CHECK(dmt.adhesion->pull_off_error == Approx(std::abs(-2.0 / maugis_pull_off(dmt.adhesion->lambda).P - 1.0)).epsilon(1e-9));
  CHECK(dmt.contact.pull_off->P == Approx(-2.0 * M_PI * 0.05 * 2e-8).epsilon(1e-12));
  CHECK_FALSE(solve_summary(parse_scene(scene_text(kTip, hs, 0.0))).adhesion);
}

TEST_CASE("the pull-off force for any lambda joins Maugis' closed form at both ends of its range", "[adhesion]") {
  CHECK(maugis_pull_off_force(1e-4 * (1 - 1e-12)) == Approx(maugis_pull_off(1e-4).P).epsilon(1e-9));
  CHECK(maugis_pull_off_force(1e4 * (1 + 1e-12)) == Approx(maugis_pull_off(1e4).P).epsilon(1e-9));
  CHECK(maugis_pull_off_force(1.0) == maugis_pull_off(1.0).P);
  CHECK(maugis_pull_off_force(1e-9) == Approx(-2.0).epsilon(1e-12));
  CHECK(maugis_pull_off_force(1e9) == Approx(-1.5).epsilon(1e-15));
  CHECK_THROWS_WITH(maugis_pull_off_force(0.0), Contains("lambda"));
}
