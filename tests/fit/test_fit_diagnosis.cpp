// Diagnoses that never contradict the data: a tip that does not indent (the sample far stiffer
// than the lever) is said with its contact slope - on a public NanoScope curve on sapphire and on
// synthetic curves across the lever's stiffness; a retract that goes clearly below the baseline
// is never reported as "no adhesion", and its pull-off is the one the data show.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/simulate.hpp"

using namespace layerjkr;

namespace {

Scene tip(double E, double w) {
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "half_space", "E": )" + format_double(E) + R"(, "nu": 0.3}, "w": )" + format_double(w) + "}",
                     "tip");
}

FitOptions free_of(std::vector<FitParameter> free, Branch b = Branch::all) {
  FitOptions o;
  o.free = std::move(free);
  o.branch = b;
  return o;
}

bool has(const std::vector<std::string>& v, const std::string& text) {
  return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.find(text) != std::string::npos; });
}

}  // namespace

TEST_CASE("a tip that does not indent is said: sapphire under a 90 N/m lever, contact slope 1.1", "[fit][diagnosis]") {
  const std::string file = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/BrukerReader_ForceCurve_Sapphire_TAP525.001";
  const CurveData c = to_curve_data(read_instrument_file(file).curves.at(0), "sapphire");
  const FitSummary s = fit(c, tip(1e9, 0.0), free_of({FitParameter::E, FitParameter::delta0, FitParameter::P0}, Branch::approach));
  INFO(s.brief_report());
  CHECK_FALSE(s.identifiable);
  CHECK(has(s.warnings, "the tip barely indents: the contact slope d(deflection)/dz is 1.1"));
  CHECK(has(s.warnings, "the deflection sensitivity itself is off by"));
}

TEST_CASE("the contact slope tells a stiff sample under a soft lever from a soft sample", "[fit][diagnosis]") {
  SimulationOptions so;
  so.max_indentation = 2e-9;
  so.noise = 2e-11;
  for (const auto& [E, k, rigid] : {std::tuple{1e11, 0.5, true}, std::tuple{1e6, 0.5, false}, std::tuple{1e9, 5000.0, false}}) {
    so.max_indentation = E > 1e10 ? 1e-9 : 2e-8;
    CurveData c = simulate_curve(tip(E, 0.0), so);
    c.spring_constant = k;
    const FitSummary s = fit(c, tip(E / 2, 0.0), free_of({FitParameter::E, FitParameter::delta0}, Branch::approach));
    INFO("E " << E << ", k " << k << "\n" << s.brief_report());
    CHECK(has(s.warnings, "the tip barely indents") == rigid);
    if (!rigid) CHECK(s.identifiable);
  }
}

TEST_CASE("a retract that goes below the baseline is never 'no adhesion', and its pull-off is the data's", "[fit][diagnosis]") {
  SimulationOptions so;
  so.max_indentation = 5e-9;
  so.noise = 1e-10;
  so.P0 = 8e-8;  // a baseline that was not zeroed, as AFM data come
  const Scene truth = tip(1e9, 0.05);
  const CurveData c = simulate_curve(truth, so);
  const double lowest = *std::min_element(c.P.begin(), c.P.end());
  const FitSummary s = fit(c, tip(3e8, 0.01), free_of({FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0}));
  INFO(s.brief_report());
  CHECK(s[FitParameter::w].value > 0.0);
  CHECK_FALSE(has(s.warnings, "the data show no adhesion"));
  CHECK(s.pull_off_force == Approx(lowest - 8e-8).epsilon(0.02));
  CHECK_THAT(s.brief_report(), Catch::Contains("measured pull-off"));
  // Fixed at w = 0 in the scene while the data dip: the fit misfits, and says so, never "no adhesion".
  const FitSummary none = fit(c, tip(3e8, 0.0), free_of({FitParameter::E, FitParameter::delta0, FitParameter::P0}));
  INFO(none.brief_report());
  CHECK_FALSE(has(none.warnings, "the data show no adhesion"));
  CHECK_FALSE(none.identifiable);
}

TEST_CASE("an approach whose baseline sits off zero fits with P0 fixed, and the offset is said", "[fit][diagnosis]") {
  // A QI-like approach of a cell: the baseline at -115 pN, as JPK's files come before the software zeroes it.
  const auto cell = [](double E) {
    return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6},
        "medium": {"type": "half_space", "E": )" + format_double(E) + R"(, "nu": 0.5}, "w": 0})", "cell");
  };
  const Scene truth = cell(2000);
  SimulationOptions so;
  so.branch = Branch::approach;
  so.max_indentation = 1e-6;
  so.noise = 5e-12;
  so.P0 = -1.15e-10;
  const CurveData c = simulate_curve(truth, so);
  const Scene start = cell(800);
  const FitOptions options = free_of({FitParameter::E, FitParameter::delta0}, Branch::approach);
  const FitSummary s = fit(c, start, options);
  INFO(s.brief_report());
  CHECK(s.baseline_offset == Approx(-1.15e-10).margin(5e-12));
  CHECK(s[FitParameter::E].value == Approx(2000).epsilon(0.02));
  CHECK(has(s.notices, "baseline"));
  CHECK(s.identifiable);
  CHECK_THAT(s.brief_report(), Catch::Contains("baseline offset"));
  // Kept as given, the same fit cannot follow the data and says so.
  FitOptions keep = options;
  keep.remove_offset = false;
  const FitSummary kept = fit(c, start, keep);
  INFO(kept.brief_report());
  CHECK(kept.baseline_offset == 0.0);
  CHECK_FALSE(kept.identifiable);
  // A baseline at zero is left alone.
  so.P0 = 0.0;
  const FitSummary zeroed = fit(simulate_curve(truth, so), start, options);
  CHECK(zeroed.baseline_offset == 0.0);
  CHECK(zeroed[FitParameter::E].value == Approx(2000).epsilon(0.02));
}

TEST_CASE("a QI curve whose last 12 of 500 samples rise 90 pN over 20 pN noise is a contact, not a sign error", "[fit][diagnosis]") {
  const auto cell = [](double E) {
    return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5.76e-6},
        "medium": {"type": "half_space", "E": )" + format_double(E) + R"(, "nu": 0.5}, "w": 0})", "qi");
  };
  SimulationOptions so;
  so.branch = Branch::approach;
  so.max_indentation = 4.8e-8;  // 90 pN at E = 2 kPa
  so.free_fraction = 488.0 / 12.0;
  so.noise = 2e-11;
  so.P0 = -1.15e-10;
  so.seed = 3;
  const CurveData c = simulate_curve(cell(2000), so);
  for (const bool P0_free : {false, true}) {
    std::vector<FitParameter> free{FitParameter::E, FitParameter::delta0};
    if (P0_free) free.push_back(FitParameter::P0);
    const FitSummary s = fit(c, cell(1000), free_of(free, Branch::approach));
    INFO(s.brief_report());
    CHECK(std::abs(s[FitParameter::E].value - 2000) < 2 * s[FitParameter::E].standard_error);
    CHECK(s[FitParameter::E].standard_error < 0.5 * 2000);
  }
  // Pure noise (a sample too soft to push back) is still no contact.
  const CurveData flat = simulate_curve(cell(1e-6), so);
  CHECK_THROWS_WITH(fit(flat, cell(1000), free_of({FitParameter::E, FitParameter::delta0}, Branch::approach)),
                    Catch::Contains("no contact region"));
}
