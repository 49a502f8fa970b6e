// Ranges of free parameters (FitOptions::bounds, #43): every solve keeps them; one that binds
// puts the parameter at its bound with no error bar and a warning, the others assessed with it
// held there; one that does not bind changes nothing; what cannot be bounded is refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

using namespace layerjkr;

namespace {

const std::string kSource = LAYERJKR_SOURCE_DIR;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The bundled hydrogel film curve: made with E = 50 kPa, w = 1e-3 J/m^2.
CurveData sample() { return read_curve_csv(kSource + "/data/curves/hydrogel_film_two_term.csv", CsvOptions{}); }
Scene sample_scene() { return load_scene(kSource + "/data/scenes/hydrogel_film_two_term.json"); }

FitOptions options(std::vector<ParameterBound> bounds = {}) {
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0};
  o.branch = Branch::all;
  o.bounds = std::move(bounds);
  return o;
}

bool warns(const FitSummary& s, const std::string& text) {
  for (const std::string& w : s.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("bounds that do not bind change nothing", "[fit][bounds]") {
  const FitSummary free_fit = fit(sample(), sample_scene(), options());
  const FitSummary bounded = fit(sample(), sample_scene(), options({{FitParameter::E, 1e3, 1e6}, {FitParameter::w, 0.0, 1.0}}));
  INFO(bounded.brief_report());
  CHECK(bounded.converged);
  for (FitParameter q : {FitParameter::E, FitParameter::w, FitParameter::delta0}) {
    CHECK(bounded[q].value == Approx(free_fit[q].value).epsilon(1e-6));
    CHECK(bounded[q].standard_error == Approx(free_fit[q].standard_error).epsilon(1e-3));
    CHECK_FALSE(bounded[q].at_bound);
  }
  CHECK_FALSE(warns(bounded, "at the end of its range"));
}

TEST_CASE("a bound that binds: the parameter at its bound, no error bar, a warning", "[fit][bounds]") {
  // The data say E = 50 kPa; a range up to 40 kPa holds it at 40 kPa.
  const FitSummary s = fit(sample(), sample_scene(), options({{FitParameter::E, -kInf, 4e4}}));
  INFO(s.brief_report());
  CHECK(s[FitParameter::E].value == Approx(4e4).epsilon(1e-9));
  CHECK(s[FitParameter::E].at_bound);
  CHECK(std::isnan(s[FitParameter::E].standard_error));
  CHECK_FALSE(s[FitParameter::E].identifiable);
  CHECK(s[FitParameter::E].reason.find("at the end 4e+04 of its range") != std::string::npos);
  CHECK(warns(s, "E = 4e+04 at the end of its range [-inf, 4e+04] (bounds)"));
  // The others' error bars come from the fit with E held there: finite.
  CHECK(std::isfinite(s[FitParameter::w].standard_error));
  CHECK(s[FitParameter::w].standard_error > 0.0);
}

TEST_CASE("a start outside its range begins at the range's edge", "[fit][bounds]") {
  Scene far = sample_scene();
  far.medium.E = 5e5;  // 10x the truth, above the range
  const FitSummary s = fit(sample(), far, options({{FitParameter::E, 1e4, 2e5}}));
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(s[FitParameter::E].value == Approx(5e4).epsilon(0.01));
  CHECK_FALSE(s[FitParameter::E].at_bound);
}

TEST_CASE("what cannot be bounded is refused, naming it", "[fit][bounds]") {
  const CurveData c = sample();
  const Scene scene = sample_scene();
  CHECK_THROWS_WITH(fit(c, scene, options({{FitParameter::R, 1e-6, 1e-5}})),
                    Catch::Contains("bounds of R: the parameter is not free"));
  CHECK_THROWS_WITH(fit(c, scene, options({{FitParameter::E, 2e4, 1e4}})), Catch::Contains("bounds of E (lower end)"));
  CHECK_THROWS_WITH(fit(c, scene, options({{FitParameter::E, std::nan(""), 1e4}})), Catch::Contains("bounds of E"));
  CHECK_THROWS_WITH(fit(c, scene, options({{FitParameter::E, 1e3, 1e5}, {FitParameter::E, 1e3, 1e6}})),
                    Catch::Contains("bounds of E given twice"));
  const FitOptions o = options({{FitParameter::E, 1e3, 1e5}});
  CHECK_THROWS_WITH(fit_joint({c, c}, scene, o), Catch::Contains("bounds are not supported in joint fits"));
  Scene relaxing = load_scene(kSource + "/data/scenes/cell_sls.json");
  CHECK_THROWS_WITH(fit(c, relaxing, o), Catch::Contains("not yet in fits in time"));
}
