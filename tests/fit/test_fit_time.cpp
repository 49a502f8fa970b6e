// Fits in time: a relaxing layer (standard linear solid) and a power-law half-space fitted to
// simulated curves give back every parameter within its error bars, alone and jointly at three
// speeds, while elastic fits of the same curves drift with the speed; a dwell is fitted; crack
// kinetics give back E, w, v_star and n; the Jacobians through Jets agree with differences of the
// residuals; what a fit in time refuses.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "fit/evaluators/curve_evaluator.hpp"
#include "fit/run/fit_steps.hpp"
#include "fit/in_time/time_evaluators.hpp"
#include "fit/in_time/time_fit.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/simulate.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

const char* kCell = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer", "E": 2000, "nu": 0.49,
    "h": 3e-6, "base": "bonded", "viscoelastic": {"law": "sls", "E_inf": 800, "tau": 0.2}}, "model": "exact"})";
// The same cell as a first guess: every law value 2.5x off.
const char* kCellGuess = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer", "E": 5000,
    "nu": 0.49, "h": 3e-6, "base": "bonded", "viscoelastic": {"law": "sls", "E_inf": 320, "tau": 0.5}}, "model": "exact"})";

CurveData cell_curve(double speed, std::uint64_t seed, double dwell = 0.0) {
  SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = speed;
  o.dwell = dwell;
  o.points_per_branch = 250;
  o.noise = 5e-11;
  o.seed = seed;
  o.delta0 = 1e-6;
  o.P0 = 1e-11;
  return simulate_curve(parse_scene(kCell), o);
}

// Within k standard errors of the truth.
void check_within(const FitSummary& s, FitParameter q, double truth, double k = 3.0) {
  const ParameterEstimate& e = s[q];
  INFO(to_string(q) << " = " << e.value << " +- " << e.standard_error << " (truth " << truth << ")");
  REQUIRE(std::isfinite(e.standard_error));
  CHECK(std::abs(e.value - truth) < k * e.standard_error);
}

FitOptions cell_options() {
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  return f;
}

}  // namespace

TEST_CASE("fit in time: three speeds of a relaxing layer, alone and jointly, give back the law", "[fit][time]") {
  const Scene guess = parse_scene(kCellGuess);
  std::vector<CurveData> curves;
  for (double v : {0.5e-6, 2e-6, 8e-6}) curves.push_back(cell_curve(v, curves.size() + 1));
  const JointFitSummary j = fit_joint(curves, guess, cell_options());
  INFO(j.fit.brief_report());
  REQUIRE(j.fit.converged);
  CHECK(j.fit.identifiable);
  CHECK(j.fit.family == FitFamily::hereditary);
  check_within(j.fit, FitParameter::E, 2000.0);
  check_within(j.fit, FitParameter::E_inf, 800.0);
  check_within(j.fit, FitParameter::tau, 0.2);
  REQUIRE(j.fit.parameters.size() == 3 + 2 * 3);
  for (std::size_t k = 0; k < 3; ++k) {
    const ParameterEstimate& d0 = j.fit.parameters[3 + 2 * k];
    CHECK(d0.parameter == FitParameter::delta0);
    CHECK(d0.curve == static_cast<int>(k));
    CHECK(std::abs(d0.value - 1e-6) < 3.0 * d0.standard_error);
  }
  CHECK(j.curve_begin.size() == 4);
  CHECK(j.curve_begin.back() == j.fit.P.size());
  // Each alone within its own (wider) error bars; the joint bars are the narrowest.
  for (const FitSummary& a : j.alone) {
    check_within(a, FitParameter::E, 2000.0);
    CHECK(a[FitParameter::E].standard_error > j.fit[FitParameter::E].standard_error);
  }
  // An elastic model of the same curves: the modulus moves with the speed (828, 1029, 1513 Pa at
  // 0.5, 2, 8 um/s on approach), far beyond its error bars.
  Scene elastic = parse_scene(kCell);
  elastic.medium.relaxation = RelaxationLaw{};
  FitOptions e;
  e.free = {FitParameter::E, FitParameter::delta0, FitParameter::P0};
  const FitSummary slow = fit(curves.front(), elastic, e), fast = fit(curves.back(), elastic, e);
  INFO("elastic: " << slow[FitParameter::E].value << " at 0.5 um/s, " << fast[FitParameter::E].value << " at 8 um/s");
  CHECK(fast[FitParameter::E].value > 1.5 * slow[FitParameter::E].value);
  CHECK(fast[FitParameter::E].value - slow[FitParameter::E].value >
        20.0 * (slow[FitParameter::E].standard_error + fast[FitParameter::E].standard_error));
  CHECK(slow[FitParameter::E].value < 2000.0 * 0.9);  // between the relaxed and instantaneous moduli
  CHECK(slow[FitParameter::E].value > 800.0);
}

TEST_CASE("fit in time: a dwell's relaxation is fitted, the branch only chooses the residuals", "[fit][time]") {
  const CurveData c = cell_curve(2e-6, 11, 0.6);
  REQUIRE(c.dwell_count() > 0);
  const FitSummary all = fit(c, parse_scene(kCellGuess), cell_options());
  INFO(all.brief_report());
  check_within(all, FitParameter::tau, 0.2);
  check_within(all, FitParameter::E_inf, 800.0);
  CHECK(all.t.size() == c.size());
  FitOptions retract = cell_options();
  retract.branch = Branch::retract;
  retract.free = {FitParameter::E, FitParameter::tau, FitParameter::P0, FitParameter::delta0};
  const FitSummary r = fit(c, parse_scene(kCell), retract);
  CHECK(r.points == c.size());  // every sample is history
  CHECK(std::any_of(r.notices.begin(), r.notices.end(),
                    [](const std::string& n) { return n.find("enter as the history") != std::string::npos; }));
  check_within(r, FitParameter::E, 2000.0);
}

TEST_CASE("fit in time: a power-law half-space gives back E and beta", "[fit][time]") {
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "half_space",
      "E": 5000, "nu": 0.5, "viscoelastic": {"law": "power_law", "beta": 0.15, "t0": 1}}})");
  SimulationOptions o;
  o.max_indentation = 1.5e-6;
  o.speed = 3e-6;
  o.points_per_branch = 300;
  o.noise = 1e-10;
  const CurveData c = simulate_curve(truth, o);
  const Scene guess = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.5, "viscoelastic": {"law": "power_law", "beta": 0.4, "t0": 1}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::delta0};
  f.branch = Branch::all;
  const FitSummary s = fit(c, guess, f);
  INFO(s.brief_report());
  REQUIRE(s.converged);
  check_within(s, FitParameter::E, 5000.0);
  check_within(s, FitParameter::beta, 0.15);
  check_within(s, FitParameter::delta0, 0.0);
}

TEST_CASE("fit in time: a power law with a plateau gives back E, beta and E_inf over noise draws", "[fit][time]") {
  // Issue 42: E(t) = E_inf + (E - E_inf)(t/t0)^-beta, approach + 3 s dwell + retract, six noise
  // draws, started 2x off in E, 2.5x in E_inf and half the true beta: every draw within 3 SE.
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": {"law": "power_law_plateau", "beta": 0.3, "t0": 1, "E_inf": 600}}})");
  const Scene guess = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 4000, "nu": 0.49, "viscoelastic": {"law": "power_law_plateau", "beta": 0.15, "t0": 1, "E_inf": 1500}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::E_inf, FitParameter::delta0};
  f.branch = Branch::all;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    SimulationOptions o;
    o.max_indentation = 1e-6;
    o.speed = 2e-6;
    o.dwell = 3.0;
    o.points_per_branch = 200;
    o.noise = 2e-12;
    o.seed = seed;
    const FitSummary s = fit(simulate_curve(truth, o), guess, f);
    INFO("seed " << seed << ": " << s.brief_report());
    REQUIRE(s.converged);
    CHECK(s.identifiable);
    check_within(s, FitParameter::E, 2000.0);
    check_within(s, FitParameter::beta, 0.3);
    check_within(s, FitParameter::E_inf, 600.0);
  }
  // E_inf belongs to the plateau law (and sls): freeing it on the plain power law is refused.
  const Scene plain = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": {"law": "power_law", "beta": 0.3, "t0": 1}}})");
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  CHECK_THROWS_WITH(fit(simulate_curve(plain, o), plain, f), Catch::Contains("power_law_plateau"));
  // The scene's E_inf must lie below E, the modulus at t0.
  CHECK_THROWS_WITH(parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": {"law": "power_law_plateau", "beta": 0.3, "t0": 1, "E_inf": 2000}}})"),
                    Catch::Contains("medium.viscoelastic.E_inf") && Catch::Contains("[0, E)"));
}

TEST_CASE("fit in time: AIC and BIC, as lmfit defines them, choose the law that made the curve", "[fit][time]") {
  // Issue 42: every fit states chi-square, AIC and BIC so that laws can be compared on one curve.
  const std::string head = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": )";
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 2e-6;
  o.dwell = 3.0;
  o.points_per_branch = 150;
  o.noise = 2e-12;
  const CurveData c = simulate_curve(parse_scene(head + R"({"law": "power_law_plateau", "beta": 0.3, "t0": 1,
      "E_inf": 600}}})"), o);
  FitOptions plateau;
  plateau.free = {FitParameter::E, FitParameter::beta, FitParameter::E_inf, FitParameter::delta0};
  plateau.branch = Branch::all;
  FitOptions power = plateau;
  power.free = {FitParameter::E, FitParameter::beta, FitParameter::delta0};
  const FitSummary with = fit(c, parse_scene(head + R"({"law": "power_law_plateau", "beta": 0.2, "t0": 1,
      "E_inf": 300}}})"), plateau);
  const FitSummary without = fit(c, parse_scene(head + R"({"law": "power_law", "beta": 0.2, "t0": 1}}})"), power);
  // The statistics from the fit's own arrays, written out (lmfit: chisqr, aic, bic).
  double chi = 0.0;
  for (std::size_t i = 0; i < with.P.size(); ++i) chi += (with.P[i] - with.P_fit[i]) * (with.P[i] - with.P_fit[i]);
  const double n = static_cast<double>(with.samples_fitted);
  CHECK(with.samples_fitted == c.size());  // every sample weighs in a fit of the whole history
  CHECK(with.chi_square() == Approx(chi).epsilon(1e-12));
  CHECK(with.reduced_chi_square() == Approx(chi / (n - 4.0)).epsilon(1e-12));
  CHECK(with.aic() == Approx(n * std::log(chi / n) + 8.0).epsilon(1e-12));
  CHECK(with.bic() == Approx(n * std::log(chi / n) + 4.0 * std::log(n)).epsilon(1e-12));
  INFO("plateau: AIC " << with.aic() << ", BIC " << with.bic() << "; plain power law: AIC " << without.aic() << ", BIC "
                       << without.bic());
  CHECK(with.aic() < without.aic() - 10.0);
  CHECK(with.bic() < without.bic() - 10.0);
  CHECK(with.brief_report().find("AIC ") != std::string::npos);
  CHECK(with.function_evaluations >= with.iterations + 1);  // the start's and at least one per iteration
}

TEST_CASE("fit in time: the lever's drag is recovered where it is and found absent where it is not", "[fit][time]") {
  // Issue 42: a lever in liquid measures b v besides the contact force (v the base's speed towards
  // the sample); simulate adds it, a fit in time frees it as drag [N s/m]. Here b v is 3 % of the
  // peak force; four noise draws with and without drag, started 2x off in E and beta.
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}})");
  const Scene guess = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 4000, "nu": 0.49, "viscoelastic": {"law": "power_law", "beta": 0.1, "t0": 1}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::drag, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  for (double b : {5e-5, 0.0})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SimulationOptions o;
      o.max_indentation = 1e-6;
      o.speed = 5e-6;
      o.points_per_branch = 200;
      o.noise = 5e-12;
      o.P0 = 1e-11;
      o.drag = b;
      o.seed = seed;
      const FitSummary s = fit(simulate_curve(truth, o), guess, f);
      INFO("drag " << b << ", seed " << seed << ": " << s.brief_report());
      REQUIRE(s.converged);
      CHECK(s.identifiable);
      check_within(s, FitParameter::drag, b);
      check_within(s, FitParameter::E, 2000.0);
      check_within(s, FitParameter::beta, 0.2);
      check_within(s, FitParameter::P0, 1e-11);
    }
  // Elastic fits and crack kinetics do not model it: refused by name, never silently dropped.
  SimulationOptions o;
  o.max_indentation = 1e-6;
  o.speed = 5e-6;
  const CurveData c = simulate_curve(truth, o);
  Scene elastic = truth;
  elastic.medium.relaxation = RelaxationLaw{};
  CHECK_THROWS_WITH(fit(c, elastic, f), Catch::Contains("drag") && Catch::Contains("relaxing medium"));
  o.speed = 0.0;
  o.drag = 1e-6;
  CHECK_THROWS_WITH(simulate_curve(truth, o), Catch::Contains("drag = 1e-06 N s/m needs a speed"));
}

TEST_CASE("fit in time: one drag shared by curves at three speeds", "[fit][time]") {
  // One lever in one liquid: b v grows with the speed while the law does not; a joint fit shares b.
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 2000, "nu": 0.49, "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}})");
  const Scene guess = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
      "E": 4000, "nu": 0.49, "viscoelastic": {"law": "power_law", "beta": 0.1, "t0": 1}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::beta, FitParameter::drag, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  const double b = 5e-5;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    std::vector<CurveData> curves;
    for (double v : {1e-6, 4e-6, 1.6e-5}) {
      SimulationOptions o;
      o.max_indentation = 1e-6;
      o.speed = v;
      o.points_per_branch = 200;
      o.noise = 5e-12;
      o.P0 = 1e-11;
      o.drag = b;
      o.seed = seed * 10 + curves.size();
      curves.push_back(simulate_curve(truth, o));
    }
    const JointFitSummary j = fit_joint(curves, guess, f);
    INFO("seed " << seed << ": " << j.fit.brief_report());
    REQUIRE(j.fit.converged);
    check_within(j.fit, FitParameter::drag, b);
    check_within(j.fit, FitParameter::E, 2000.0);
    check_within(j.fit, FitParameter::beta, 0.2);
    // Shared, the drag's error bar is below each curve's own.
    for (const FitSummary& alone : j.alone) CHECK(j.fit[FitParameter::drag].standard_error < alone[FitParameter::drag].standard_error);
  }
}

TEST_CASE("fit in time: the hereditary Jacobian through Jets against differences of the residuals", "[fit][time]") {
  for (const char* law : {R"({"law": "sls", "E_inf": 800, "tau": 0.2})", R"({"law": "power_law", "beta": 0.2, "t0": 1})"}) {
    const Scene s = parse_scene(std::string(R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer",
        "E": 2000, "nu": 0.49, "h": 3e-6, "base": "bonded", "viscoelastic": )") + law + R"(}, "model": "exact"})");
    SimulationOptions o;
    o.max_indentation = 2e-6;
    o.speed = 2e-6;
    o.points_per_branch = 80;
    o.delta0 = 1e-7;
    CurveData c = simulate_curve(s, o);
    FitOptions f;
    f.free = s.medium.relaxation.kind == RelaxationLaw::Kind::power_law
                 ? std::vector<FitParameter>{FitParameter::E, FitParameter::beta, FitParameter::delta0, FitParameter::P0}
                 : std::vector<FitParameter>{FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0, FitParameter::P0};
    detail::FitData data;
    double span = 0.0, force_span = 0.0;
    data = detail::select_time_data(c, f, &span, &force_span);
    detail::SceneParameters fixed;
    const Scene el = detail::elastic_scene(s);
    const auto model = detail::make_curve_model(el, resolve_model(el), f, span, &fixed);
    detail::law_values(s, &fixed);
    const detail::ParameterMap map = detail::make_parameter_map(f, resolve_model(el), fixed, span, force_span);
    detail::HereditaryEvaluator ev(*model, map, data, s.medium.relaxation);
    const std::vector<double> x{0.05, -0.03, 0.02, 0.01, 0.02};
    std::vector<double> xv(x.begin(), x.begin() + static_cast<long>(f.free.size()));
    REQUIRE(ev.evaluate(xv.data(), true));
    const std::vector<double> J = ev.jacobian();
    const std::size_t n = f.free.size();
    double worst = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double h = 1e-6;
      std::vector<double> xp = xv, xm = xv;
      xp[j] += h;
      xm[j] -= h;
      REQUIRE(ev.evaluate(xp.data(), false));
      const std::vector<double> rp = ev.residuals();
      REQUIRE(ev.evaluate(xm.data(), false));
      const std::vector<double> rm = ev.residuals();
      double scale = 0.0;
      for (std::size_t i = 0; i < rp.size(); ++i) scale = std::max(scale, std::abs(J[i * n + j]));
      for (std::size_t i = 0; i < rp.size(); ++i)
        worst = std::max(worst, std::abs((rp[i] - rm[i]) / (2 * h) - J[i * n + j]) / scale);
    }
    INFO(s.medium.relaxation.describe() << ": largest difference " << worst << " of each column's largest entry");
    CHECK(worst < 1e-5);
  }
}

TEST_CASE("fit in time: crack kinetics give back E, w, v_star and n", "[fit][time]") {
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space",
      "E": 1e6, "nu": 0.5}, "w": 0.05, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})");
  SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = 1e-6;
  o.points_per_branch = 200;
  o.noise = 2e-6;
  o.delta0 = 1e-6;
  const CurveData c = simulate_curve(truth, o);
  const Scene guess = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space",
      "E": 1e6, "nu": 0.5}, "w": 0.03, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-5, "n": 0.5}}})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::w, FitParameter::v_star, FitParameter::n, FitParameter::delta0};
  f.branch = Branch::all;
  const FitSummary s = fit(c, guess, f);
  INFO(s.brief_report());
  REQUIRE(s.converged);
  CHECK(s.family == FitFamily::kinetic);
  check_within(s, FitParameter::E, 1e6);
  check_within(s, FitParameter::w, 0.05);
  check_within(s, FitParameter::v_star, 1e-6);
  check_within(s, FitParameter::n, 0.6);
}

TEST_CASE("fit in time refuses what it cannot fit, naming why", "[fit][time]") {
  const Scene cell = parse_scene(kCell);
  CurveData c = cell_curve(2e-6, 5);
  FitOptions f = cell_options();
  const auto refused = [&](const CurveData& curve, const Scene& scene, const FitOptions& o) {
    try {
      fit(curve, scene, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  CurveData untimed = c;
  untimed.t.clear();
  CHECK_THAT(refused(untimed, cell, f), Catch::Contains("is fitted in time") && Catch::Contains("has no time"));
  FitOptions o = f;
  o.free = {FitParameter::E, FitParameter::beta};
  CHECK_THAT(refused(c, cell, o), Catch::Contains("beta is a power law's"));
  o.free = {FitParameter::E, FitParameter::v_star};
  CHECK_THAT(refused(c, cell, o), Catch::Contains("v_star belongs to crack kinetics"));
  o.free = {FitParameter::E, FitParameter::w};
  CHECK_THAT(refused(c, cell, o), Catch::Contains("is fitted on a relaxing medium where the scene models its adhesion"));
  o = f;
  o.contact_point = ContactPointMethod::rov;
  CHECK_THAT(refused(c, cell, o), Catch::Contains("no contact-point method"));
  o = f;
  o.indentation_range = Interval{0.0, 1e-6};
  CHECK_THAT(refused(c, cell, o), Catch::Contains("no indentation or force range"));
  Scene elastic = cell;
  elastic.medium.relaxation = RelaxationLaw{};
  o.free = {FitParameter::E, FitParameter::tau};
  o.indentation_range.reset();
  CHECK_THAT(refused(c, elastic, o), Catch::Contains("tau belongs to a law in time") && Catch::Contains("which this scene has not"));
  CHECK_THROWS_WITH(fit_joint({c, c}, elastic, f), Catch::Contains("shares a law in time"));
  CHECK_THROWS_WITH(fit_joint({c}, cell, f), Catch::Contains("at least 2 curves"));
  CurveData late = c;  // no sample before the contact: the history's start is unknown
  for (double& d : late.delta) d += 10e-6;
  o = f;
  o.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau};
  late.source = "late.csv";
  CHECK_THROWS_WITH(fit_joint({late, c}, cell, o), Catch::Contains("fit_joint: late.csv cannot be fitted alone"));
}
