// Real AFM data (../shared/data/real, nanite peer fits): the Hertz fit must reproduce
// the peer's E and contact point. Skipped, not failed, when ../shared is absent.
#include <catch2/catch.hpp>

#include <fstream>

#include <nlohmann/json.hpp>

#include "layerjkr/fit.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
const std::string kReal = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/real/";
bool have_real_data() { return std::ifstream(kReal + "reference_fits.json").good(); }
}  // namespace

TEST_CASE("jpk_spot3_0192: E and contact point match nanite to 1e-4", "[fit][real]") {
  if (!have_real_data()) {
    test::report_skip(kReal + " is absent (the shared data beside the repository)");
    return;
  }
  const nlohmann::json meta = nlohmann::json::parse(std::ifstream(kReal + "jpk_spot3_0192_meta.json"));
  const double E_ref = meta["fit"]["E_Pa"], cp_ref = meta["fit"]["contact_point_m"];
  // tip_position,force: delta = -tip_position, so the contact point is -delta0.
  const CurveData data = read_curve_csv(kReal + "jpk_spot3_0192_approach.csv");
  REQUIRE(data.size() == 276);
  const Scene scene = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 4e-8},
      "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}})");
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::delta0};
  o.branch = Branch::all;  // the file holds the fitted window of the approach only
  const FitSummary s = fit(data, scene, o);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, E_ref) < 1e-4);
  CHECK(rel_err(-s[FitParameter::delta0].value, cp_ref) < 1e-4);
  CHECK(rel_err(s[FitParameter::E].standard_error, meta["fit"]["E_stderr_Pa"].get<double>()) < 1e-2);
  CHECK(rel_err(s[FitParameter::delta0].standard_error, meta["fit"]["contact_point_stderr_m"].get<double>()) < 1e-2);
}

TEST_CASE("every unweighted reference fit is reproduced to 1e-4", "[fit][real]") {
  if (!have_real_data()) {
    test::report_skip(kReal + " is absent (the shared data beside the repository)");
    return;
  }
  const nlohmann::json fits = nlohmann::json::parse(std::ifstream(kReal + "reference_fits.json"));
  int checked = 0;
  for (const auto& f : fits) {
    // nanite_default multiplies residuals by min(|x - cp|/1um, 1): not a plain least squares.
    if (f["weight_cp_m"].get<double>() != 0.0) continue;
    const CurveData data = read_curve_csv(kReal + f["data_csv"].get<std::string>());
    Scene scene = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
        "medium": {"type": "half_space", "E": 3e3, "nu": 0.5}})");
    scene.profile = make_paraboloid(f["R"].get<double>());
    scene.medium.nu = f["nu"].get<double>();
    FitOptions o;
    o.free = {FitParameter::E, FitParameter::delta0};
    if (f["baseline_vary"].get<bool>()) o.free.push_back(FitParameter::P0);
    o.branch = Branch::all;
    // The exports are nanite's preprocessed curves, its own offset already removed: its fit
    // takes them as they are, and so must this one to reproduce it.
    o.remove_offset = false;
    const FitSummary s = fit(data, scene, o);
    INFO(f["data_csv"] << " " << f["variant"] << "\n" << s.brief_report());
    CHECK(s.converged);
    CHECK(rel_err(s[FitParameter::E].value, f["E"].get<double>()) < 1e-4);
    CHECK(rel_err(s[FitParameter::delta0].value, -f["contact_point"].get<double>()) < 1e-4);
    ++checked;
  }
  CHECK(checked >= 3);
}
