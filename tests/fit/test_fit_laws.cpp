// Fits in time with the laws users fit (issue 42): a fractional standard linear solid gives back E,
// beta, tau and E_inf over noise draws from a start 2x off, the fractional Maxwell model E, beta and
// tau, the two-term generalised Maxwell law E, E_inf, tau, E_2 and tau_2; AIC and BIC tell the
// fractional law from the power law with a plateau on a curve one of them made; the fitted values
// land in the scene's keys; what the laws refuse.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

const std::string kHead = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
    "E": %E, "nu": 0.49, "viscoelastic": )";

Scene scene_with(double E, const std::string& law) {
  std::string head = kHead;
  head.replace(head.find("%E"), 2, std::to_string(E));
  return parse_scene(head + law + "}}");
}

// Approach at 2 um/s to 1 um, a 3 s dwell, the retract: 2 pN noise on a ~100 pN peak.
CurveData dwell_curve(const Scene& truth, std::uint64_t seed) {
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  o.dwell = 3.0;
  o.points_per_branch = 200;
  o.noise = 2e-12;
  o.seed = seed;
  return simulate_curve(truth, o);
}

void check_within(const FitSummary& s, FitParameter q, double truth) {
  const ParameterEstimate& e = s[q];
  INFO(to_string(q) << " = " << e.value << " +- " << e.standard_error << " (truth " << truth << ")");
  REQUIRE(std::isfinite(e.standard_error));
  CHECK(std::abs(e.value - truth) < 3.0 * e.standard_error);
}

}  // namespace

TEST_CASE("fit in time: a fractional SLS gives back E, beta, tau and E_inf over noise draws from 2x off", "[fit][time]") {
  const Scene truth = scene_with(2000, R"({"law": "fractional_sls", "beta": 0.4, "tau": 0.5, "E_inf": 500})");
  const Scene guess = scene_with(4000, R"({"law": "fractional_sls", "beta": 0.2, "tau": 1.0, "E_inf": 1000})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::tau, FitParameter::E_inf, FitParameter::delta0};
  f.branch = Branch::all;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const FitSummary s = fit(dwell_curve(truth, seed), guess, f);
    INFO("seed " << seed << ": " << s.brief_report());
    REQUIRE(s.converged);
    CHECK(s.identifiable);
    check_within(s, FitParameter::E, 2000.0);
    check_within(s, FitParameter::beta, 0.4);
    check_within(s, FitParameter::tau, 0.5);
    check_within(s, FitParameter::E_inf, 500.0);
    if (seed == 1) {
      // The fitted values go back into the scene's own keys.
      const Scene fitted = fitted_scene(guess, s.parameters);
      CHECK(fitted.medium.relaxation.beta == Approx(s[FitParameter::beta].value));
      CHECK(fitted.medium.relaxation.tau_f == Approx(s[FitParameter::tau].value));
      CHECK(fitted.medium.relaxation.plateau * s[FitParameter::E].value == Approx(s[FitParameter::E_inf].value));
    }
  }
}

TEST_CASE("fit in time: the fractional Maxwell model gives back E, beta and tau over noise draws", "[fit][time]") {
  const Scene truth = scene_with(3000, R"({"law": "fractional_maxwell", "beta": 0.5, "tau": 0.5})");
  const Scene guess = scene_with(1500, R"({"law": "fractional_maxwell", "beta": 0.25, "tau": 1.0})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::tau, FitParameter::delta0};
  f.branch = Branch::all;
  for (std::uint64_t seed = 11; seed <= 14; ++seed) {
    const FitSummary s = fit(dwell_curve(truth, seed), guess, f);
    INFO("seed " << seed << ": " << s.brief_report());
    REQUIRE(s.converged);
    check_within(s, FitParameter::E, 3000.0);
    check_within(s, FitParameter::beta, 0.5);
    check_within(s, FitParameter::tau, 0.5);
  }
  // At beta = 0.25 the law is a power law over most of the history ((t/tau)^-beta: only E tau^beta
  // is told): E, beta and tau trade off, and the fit says so rather than give a confident error bar.
  const FitSummary slow = fit(dwell_curve(scene_with(3000, R"({"law": "fractional_maxwell", "beta": 0.25, "tau": 2.0})"), 11),
                              guess, f);
  INFO(slow.brief_report());
  CHECK_FALSE(slow.identifiable);
  CHECK_FALSE(std::isfinite(slow[FitParameter::tau].standard_error));
  // No plateau to free on the Maxwell model.
  FitOptions with_plateau = f;
  with_plateau.free.push_back(FitParameter::E_inf);
  CHECK_THROWS_WITH(fit(dwell_curve(truth, 1), guess, with_plateau), Catch::Contains("fractional_sls"));
}

TEST_CASE("fit in time: AIC and BIC tell the fractional SLS from the power law with a plateau", "[fit][time]") {
  const CurveData c = dwell_curve(scene_with(2000, R"({"law": "fractional_sls", "beta": 0.5, "tau": 0.3, "E_inf": 400})"), 5);
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::tau, FitParameter::E_inf, FitParameter::delta0};
  f.branch = Branch::all;
  const FitSummary fractional =
      fit(c, scene_with(3000, R"({"law": "fractional_sls", "beta": 0.3, "tau": 1.0, "E_inf": 800})"), f);
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::E_inf, FitParameter::delta0};
  const FitSummary plateau =
      fit(c, scene_with(3000, R"({"law": "power_law_plateau", "beta": 0.3, "t0": 1, "E_inf": 800})"), f);
  INFO("fractional SLS: AIC " << fractional.aic() << ", BIC " << fractional.bic() << "; power law with plateau: AIC "
                              << plateau.aic() << ", BIC " << plateau.bic());
  CHECK(fractional.aic() < plateau.aic() - 10.0);
  CHECK(fractional.bic() < plateau.bic() - 10.0);
}

TEST_CASE("scene: the fractional laws' keys and ranges", "[fit][time]") {
  const Scene s = scene_with(2000, R"({"law": "fractional_sls", "beta": 0.4, "tau": 0.5, "E_inf": 500})");
  CHECK(s.medium.relaxation.kind == RelaxationLaw::Kind::fractional);
  CHECK(s.medium.relaxation.plateau == Approx(0.25));
  CHECK_THROWS_WITH(scene_with(2000, R"({"law": "fractional_sls", "beta": 0.4, "tau": 0.5, "E_inf": 2500})"),
                    Catch::Contains("medium.viscoelastic.E_inf") && Catch::Contains("[0, E)"));
  CHECK_THROWS_WITH(scene_with(2000, R"({"law": "fractional_maxwell", "beta": 0.4, "tau": 0.5, "E_inf": 10})"),
                    Catch::Contains("E_inf"));
  CHECK_THROWS_WITH(scene_with(2000, R"({"law": "fractional_maxwell", "beta": 1.0, "tau": 0.5})"),
                    Catch::Contains("beta") && Catch::Contains("[0.01, 0.95]"));
  CHECK_THROWS_WITH(scene_with(2000, R"({"law": "fractional_kv", "beta": 0.4})"), Catch::Contains("fractional_maxwell"));
}

TEST_CASE("fit in time: a two-term Maxwell law gives back both arms over noise draws from 2x off", "[fit][time]") {
  // E(t) = E_inf + (E - E_inf - E_2) exp(-t/tau) + E_2 exp(-t/tau_2): a fast arm (0.1 s) and a slow
  // one (2 s) over approach, a 5 s dwell and the retract.
  const Scene truth = scene_with(3000, R"({"law": "maxwell2", "E_inf": 500, "tau": 0.1, "E_2": 800, "tau_2": 2.0})");
  const Scene guess = scene_with(6000, R"({"law": "maxwell2", "E_inf": 1000, "tau": 0.2, "E_2": 1600, "tau_2": 4.0})");
  FitOptions f;
  f.free = {FitParameter::E,   FitParameter::E_inf, FitParameter::tau,
            FitParameter::E_2, FitParameter::tau_2, FitParameter::delta0};
  f.branch = Branch::all;
  for (std::uint64_t seed = 21; seed <= 26; ++seed) {
    SimulationOptions o;
    o.max_indentation = 1e-6;
    o.speed = 2e-6;
    o.dwell = 5.0;
    o.points_per_branch = 200;
    o.noise = 2e-12;
    o.seed = seed;
    const FitSummary s = fit(simulate_curve(truth, o), guess, f);
    INFO("seed " << seed << ": " << s.brief_report());
    REQUIRE(s.converged);
    CHECK(s.identifiable);
    check_within(s, FitParameter::E, 3000.0);
    check_within(s, FitParameter::E_inf, 500.0);
    check_within(s, FitParameter::tau, 0.1);
    check_within(s, FitParameter::E_2, 800.0);
    check_within(s, FitParameter::tau_2, 2.0);
    if (seed == 21) {
      const Scene fitted = fitted_scene(guess, s.parameters);
      const RelaxationLaw& law = fitted.medium.relaxation;
      CHECK(law.two_term_form);
      CHECK(law.tau[1] == Approx(s[FitParameter::tau_2].value));
      CHECK(law.g[1] * s[FitParameter::E].value == Approx(s[FitParameter::E_2].value));
    }
  }
  // The second arm is maxwell2's alone; its moduli must leave the first arm a positive one.
  FitOptions sls = f;
  sls.free = {FitParameter::E, FitParameter::E_2, FitParameter::delta0};
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  const Scene one = scene_with(3000, R"({"law": "sls", "E_inf": 500, "tau": 0.1})");
  CHECK_THROWS_WITH(fit(simulate_curve(one, o), one, sls), Catch::Contains("maxwell2"));
  CHECK_THROWS_WITH(scene_with(3000, R"({"law": "maxwell2", "E_inf": 2000, "tau": 0.1, "E_2": 1000, "tau_2": 2})"),
                    Catch::Contains("E_inf + E_2 < E"));
}
