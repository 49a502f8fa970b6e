// Dwell segments fitted in time (issue 42): the dwell branches (the dwell alone, or with the
// approach; what precedes enters as history) give back the law; what an elastic fit and a curve
// without a dwell refuse; and where a law misses, the report names it and measures it - a second
// time scale the law lacks, a drifting baseline, adhesion on the retract - on simulated curves
// whose truth is known, and on afmformats' real stress-relaxation and creep curves.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <string>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

Scene half_space(const std::string& law, double E = 2000) {
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space", "E": )" +
                     std::to_string(E) + R"(, "nu": 0.49, "viscoelastic": )" + law + "}}");
}

CurveData dwell_curve(const Scene& truth, std::uint64_t seed, double dwell = 3.0) {
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  o.dwell = dwell;
  o.points_per_branch = 200;
  o.noise = 2e-12;
  o.seed = seed;
  return simulate_curve(truth, o);
}

std::string misfit_warning(const FitSummary& s) {
  for (const std::string& w : s.warnings)
    if (w.rfind("where the law misses", 0) == 0) return w;
  return "";
}

// The number after `key` in `text` (NaN without it).
double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + key.size()));
}

}  // namespace

TEST_CASE("fit in time: the dwell branches give back the law, and elastic fits and curves without a dwell refuse them",
          "[fit][time]") {
  const Scene truth = half_space(R"({"law": "sls", "E_inf": 600, "tau": 0.8})");
  const Scene guess = half_space(R"({"law": "sls", "E_inf": 1200, "tau": 1.6})", 4000);
  FitOptions f;
  for (Branch b : {Branch::dwell, Branch::approach_dwell})
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      f.branch = b;
      // A dwell alone rests at one indentation: its force scales as E (delta - delta0)^1.5, so E and
      // the contact point trade off there (the fit says so); the approach tells delta0.
      f.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau};
      if (b == Branch::approach_dwell) f.free.push_back(FitParameter::delta0);
      const CurveData c = dwell_curve(truth, seed);
      const FitSummary s = fit(c, guess, f);
      INFO(to_string(b) << ", seed " << seed << ": " << s.brief_report());
      REQUIRE(s.converged);
      for (auto [q, value] : {std::pair{FitParameter::E, 2000.0}, {FitParameter::E_inf, 600.0}, {FitParameter::tau, 0.8}}) {
        INFO(to_string(q));
        CHECK(std::abs(s[q].value - value) < 3.0 * s[q].standard_error);
      }
      // The dwell branch weighs the dwell's samples only; the retract never enters.
      std::size_t approach = 0, dwell = 0;
      for (int seg : c.segment) (seg == 0 ? approach : seg == 2 ? dwell : approach) += seg == 1 ? 0 : 1;
      CHECK(s.samples_fitted == (b == Branch::dwell ? dwell : approach + dwell));
      CHECK(misfit_warning(s).empty());
    }
  f.branch = Branch::dwell;
  CHECK_THROWS_WITH(fit(dwell_curve(truth, 1, 0.0), guess, f), Catch::Contains("needs a dwell"));
  // Freeing delta0 on the dwell alone: E and delta0 are reported as not separable, not given error bars.
  f.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0};
  const FitSummary alone = fit(dwell_curve(truth, 1), guess, f);
  CHECK_FALSE(alone.identifiable);
  CHECK_FALSE(std::isfinite(alone[FitParameter::E].standard_error));
  Scene elastic = guess;
  elastic.medium.relaxation = RelaxationLaw{};
  f.free = {FitParameter::E, FitParameter::delta0};
  CHECK_THROWS_WITH(fit(dwell_curve(truth, 1), elastic, f), Catch::Contains("fitted in time"));
}

TEST_CASE("fit in time: a law that misses is told where and by how much", "[fit][time]") {
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  const Scene sls = half_space(R"({"law": "sls", "E_inf": 1000, "tau": 0.5})");
  SECTION("a second time scale: two exponentials fitted with one") {
    // g = 0.3 at 0.05 s and 0.3 at 2 s: an SLS takes one; the other, tau2 near 2 s or 0.05 s, is named.
    const FitSummary s = fit(dwell_curve(half_space(R"({"law": "prony", "g": [0.3, 0.3], "tau": [0.05, 2.0]})"), 1, 6.0), sls, f);
    const std::string w = misfit_warning(s);
    INFO(s.brief_report());
    REQUIRE_FALSE(w.empty());
    CHECK(w.find("a second time scale the law lacks") != std::string::npos);
    const double tau2 = number_after(w, "one exponential of tau2 = ");
    CHECK(((tau2 > 0.5 && tau2 < 8.0) || (tau2 > 0.0125 && tau2 < 0.2)));
  }
  SECTION("a drifting baseline: the step from start to end, measured") {
    CurveData c = dwell_curve(sls, 2);
    const double rate = 2e-12;  // N/s over ~5.5 s: 11 pN, 5.5 noise sigmas
    for (std::size_t i = 0; i < c.size(); ++i) c.P[i] += rate * c.t[i];
    const FitSummary s = fit(c, sls, f);
    const std::string w = misfit_warning(s);
    INFO(s.brief_report());
    REQUIRE_FALSE(w.empty());
    const double step = number_after(w, "the baseline steps by ");
    const double truth = rate * (c.t.back() - c.t.front());
    CHECK(step > 0.5 * truth);
    CHECK(step < 1.5 * truth);
  }
  SECTION("adhesion on the retract") {
    CurveData c = dwell_curve(sls, 3);
    // A 40 pN dip where the retract lets go, over 40 samples: adhesion the relaxing medium does not model.
    std::size_t lowest = 0;
    for (std::size_t i = 0; i < c.size(); ++i)
      if (c.segment[i] == 1 && c.delta[i] > 0.0) lowest = i;
    REQUIRE(lowest > 40);
    for (std::size_t i = lowest - 40; i <= lowest; ++i) c.P[i] -= 4e-11 * static_cast<double>(i - (lowest - 40)) / 40.0;
    const FitSummary s = fit(c, sls, f);
    const std::string w = misfit_warning(s);
    INFO(s.brief_report());
    REQUIRE_FALSE(w.empty());
    CHECK(w.find("adhesion") != std::string::npos);
    CHECK(number_after(w, "the retract's lowest force lies ") == Approx(4e-11).epsilon(0.3));
  }
}

TEST_CASE("fit in time: afmformats' dwell curves - the creep's dwell described, the stress relaxation's misfit named",
          "[fit][time][real]") {
  const std::string dir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
  const std::string creep = dir + "fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force";
  const std::string relax = dir + "fmt-jpk-sr_cell1-0008.jpk-force";
  if (!std::ifstream(creep).good() || !std::ifstream(relax).good()) {
    WARN("skipped: needs ../shared/data/instrument (afmformats' dwell curves)");
    return;
  }
  const Scene fractional = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type":
      "half_space", "E": 1000, "nu": 0.5, "viscoelastic": {"law": "fractional_sls", "beta": 0.4, "tau": 1, "E_inf": 200}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::tau, FitParameter::E_inf, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::dwell;
  // The creep's 3 s at constant force: its residuals are noise (within 3x of it, without structure).
  const FitSummary c = fit(to_curve_data(InstrumentReader(creep).curve(0), creep), fractional, f);
  INFO(c.brief_report());
  CHECK(c.converged);
  CHECK_FALSE(c.residual_structure);
  CHECK(c.rms_residual < 3.0 * c.noise);
  // The stress relaxation's whole history: the report names each feature the law misses, measured.
  Scene power = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 1000, "nu": 0.5, "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}})");
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  const FitSummary r = fit(to_curve_data(InstrumentReader(relax).curve(0), relax), power, f);
  const std::string w = misfit_warning(r);
  INFO(r.brief_report());
  REQUIRE_FALSE(w.empty());
  CHECK(w.find("the dwell") != std::string::npos);
  CHECK(w.find("adhesion") != std::string::npos);
  CHECK(number_after(w, "the baseline steps by ") < -5e-8);  // the retract ends ~80 nN below the start
}
