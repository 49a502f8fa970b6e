// Parameter identification: recovery, coverage of the error bars, identifiability,
// robustness of the start, robust losses, and bad data.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <boost/math/constants/constants.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/simulate.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

constexpr double kPi = boost::math::constants::pi<double>();

Scene scene_from(const std::string& json) { return parse_scene(json, "test scene"); }

// Retract branch of classical JKR on a half-space, sampled in a from the closed forms
// (independent of every solver in the library): delta = a^2/R - sqrt(2 pi w a/E*),
// P = 4E* a^3/(3R) - sqrt(8 pi w E* a^3), free after pull-off a_po^3 = 9 pi w R^2/(8 E*).
CurveData jkr_half_space_retract(double E_star, double w, double R, double d0, double P0,
                                 double noise, unsigned seed, std::size_t n) {
  const double a_po = std::cbrt(9.0 * kPi * w * R * R / (8.0 * E_star));
  const double a_max = 5.0 * a_po;
  auto delta = [&](double a) { return a * a / R - std::sqrt(2.0 * kPi * w * a / E_star); };
  auto force = [&](double a) {
    return 4.0 * E_star * a * a * a / (3.0 * R) - std::sqrt(8.0 * kPi * w * E_star * a * a * a);
  };
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  for (std::size_t i = 0; i < n; ++i) {  // in contact: a from a_max down to a_po
    const double a = a_max - (a_max - a_po) * i / (n - 1.0);
    c.delta.push_back(delta(a) + d0);
    c.P.push_back(force(a) + P0 + noise * g(rng));
    c.segment.push_back(1);
  }
  const double d_po = delta(a_po), span = delta(a_max) - d_po;
  for (std::size_t i = 1; i <= n / 2; ++i) {  // free after pull-off
    c.delta.push_back(d_po - span * i / n + d0);
    c.P.push_back(P0 + noise * g(rng));
    c.segment.push_back(1);
  }
  return c;
}

FitOptions options(std::vector<FitParameter> free, Branch b = Branch::retract) {
  FitOptions o;
  o.free = std::move(free);
  o.branch = b;
  return o;
}

}  // namespace

TEST_CASE("half-space JKR from closed forms: E, w, delta0, P0 recovered within the error bars", "[fit]") {
  const double nu = 0.5, E = 2e6, E_star = E / (1 - nu * nu), w = 0.05, R = 1e-4;
  const double d0 = 2e-6, P0 = 3e-7;
  const Scene scene = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-4},
      "medium": {"type": "half_space", "E": 5e4, "nu": 0.5}})");  // E 40x off, w absent
  SECTION("noiseless data: exact recovery") {
    const CurveData c = jkr_half_space_retract(E_star, w, R, d0, P0, 0.0, 1, 400);
    const FitSummary s = fit(c, scene, options({FitParameter::E, FitParameter::w,
                                                FitParameter::delta0, FitParameter::P0}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(s.family == FitFamily::hertz);
    CHECK(rel_err(s[FitParameter::E].value, E) < 1e-8);
    CHECK(rel_err(s[FitParameter::w].value, w) < 1e-8);
    CHECK(std::abs(s[FitParameter::delta0].value - d0) < 1e-8 * R);
    CHECK(s.rms_residual < 1e-10 * 1.5 * kPi * w * R);
    CHECK(s.identifiable);
  }
  SECTION("noisy data: within 4 standard errors") {
    const double noise = 0.02 * 1.5 * kPi * w * R;
    const CurveData c = jkr_half_space_retract(E_star, w, R, d0, P0, noise, 7, 400);
    const FitSummary s = fit(c, scene, options({FitParameter::E, FitParameter::w,
                                                FitParameter::delta0, FitParameter::P0}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(std::abs(s[FitParameter::E].value - E) < 4 * s[FitParameter::E].standard_error);
    CHECK(std::abs(s[FitParameter::w].value - w) < 4 * s[FitParameter::w].standard_error);
    CHECK(std::abs(s[FitParameter::delta0].value - d0) < 4 * s[FitParameter::delta0].standard_error);
    CHECK(rel_err(s.rms_residual, noise) < 0.15);
    CHECK(s[FitParameter::E].standard_error < 0.05 * E);
  }
}

TEST_CASE("error bars cover the truth at the nominal rate over many seeds", "[fit][coverage]") {
  // Two-term retract curves with noise; ~68 % of |estimate - truth| must fall within one
  // standard error. 200 seeds: the binomial spread of the rate is 0.033.
  const Scene truth = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "pasternak", "K": 1e12, "G": 20}, "model": "asymptotic", "w": 0.05})");
  Scene guess = truth;
  guess.medium.K = 3e10;
  guess.w = 0.0;
  SimulationOptions so;
  so.branch = Branch::retract;
  so.points_per_branch = 200;
  so.max_indentation = 2e-6;
  so.delta0 = 1e-6;
  so.P0 = 0.0;
  so.noise = 2e-5;
  const FitOptions o = options({FitParameter::K, FitParameter::w, FitParameter::delta0, FitParameter::P0});
  int inside_K = 0, inside_w = 0, inside_d0 = 0, n = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    so.seed = seed;
    const FitSummary s = fit(simulate_curve(truth, so), guess, o);
    REQUIRE(s.converged);
    ++n;
    inside_K += std::abs(s[FitParameter::K].value - 1e12) < s[FitParameter::K].standard_error;
    inside_w += std::abs(s[FitParameter::w].value - 0.05) < s[FitParameter::w].standard_error;
    inside_d0 += std::abs(s[FitParameter::delta0].value - 1e-6) < s[FitParameter::delta0].standard_error;
  }
  for (int inside : {inside_K, inside_w, inside_d0}) {
    INFO("coverage " << double(inside) / n);
    CHECK(double(inside) / n > 0.58);
    CHECK(double(inside) / n < 0.78);
  }
}

TEST_CASE("every family recovers noiseless synthetic data", "[fit][families]") {
  struct Case {
    std::string name, scene;
    std::vector<FitParameter> free;
    double E_or_K, tol;
  };
  const std::vector<Case> cases = {
      {"winkler", R"({"indenter": {"shape": "sphere", "R": 1e-3}, "medium": {"type": "winkler", "K": 2e11}, "w": 0.02})",
       {FitParameter::K, FitParameter::w, FitParameter::delta0}, 2e11, 1e-7},
      {"layer two_term via E", R"({"indenter": {"shape": "paraboloid", "R": 5e-3}, "medium": {"type": "layer", "E": 1e6, "nu": 0.3, "h": 2e-5}, "model": "two_term", "w": 0.03})",
       {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0}, 1e6, 1e-7},
      {"full pasternak K and G", R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "pasternak", "K": 1e12, "G": 200}, "model": "full", "w": 0.05})",
       {FitParameter::K, FitParameter::G, FitParameter::w, FitParameter::delta0}, 1e12, 1e-6},
      {"filonenko-borodich cone", R"({"indenter": {"shape": "cone", "semi_angle_deg": 80}, "medium": {"type": "filonenko_borodich", "K": 1e12, "T": 50}, "model": "full", "w": 0.02})",
       {FitParameter::K, FitParameter::w, FitParameter::delta0}, 1e12, 1e-6},
      {"half-space sphere (tabulated)", R"({"indenter": {"shape": "sphere", "R": 1e-4}, "medium": {"type": "half_space", "E": 1e6, "nu": 0.4}, "w": 0.05})",
       {FitParameter::E, FitParameter::w, FitParameter::delta0}, 1e6, 1e-5},
      {"exact layer (tabulated)", R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "layer", "E": 1e6, "nu": 0.45, "h": 5e-5}, "model": "exact", "w": 0.05})",
       {FitParameter::E, FitParameter::w, FitParameter::delta0}, 1e6, 1e-5},
      {"edge-corrected layer (tabulated)", R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "layer", "E": 1e6, "nu": 0.3, "h": 2e-5, "base": "frictionless"}, "model": "edge_corrected", "w": 0.05})",
       {FitParameter::E, FitParameter::w, FitParameter::delta0}, 1e6, 1e-5},
  };
  for (const Case& c : cases) {
    DYNAMIC_SECTION(c.name) {
      const Scene truth = scene_from(c.scene);
      SimulationOptions so;
      so.points_per_branch = 150;
      so.delta0 = 5e-7;
      so.max_indentation = truth.medium.type == MediumType::half_space ? 2e-6 : 4e-6;
      const CurveData data = simulate_curve(truth, so);
      Scene guess = truth;
      guess.w = 0.0;
      guess.medium.K *= 20.0;
      guess.medium.E *= 20.0;
      const FitSummary s = fit(data, guess, options(c.free, Branch::all));
      INFO(s.brief_report());
      CHECK(s.converged);
      const bool by_E = std::find(c.free.begin(), c.free.end(), FitParameter::E) != c.free.end();
      CHECK(rel_err(s[by_E ? FitParameter::E : FitParameter::K].value, c.E_or_K) < c.tol);
      CHECK(rel_err(s[FitParameter::w].value, truth.w) < 10 * c.tol);
      CHECK(std::abs(s[FitParameter::delta0].value - 5e-7) < 10 * c.tol * so.max_indentation);
    }
  }
}

TEST_CASE("a paraboloid with a free contact point cannot identify G (theory.md s.1)", "[fit][identifiability]") {
  const Scene truth = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "pasternak", "K": 1e12, "G": 50}, "model": "asymptotic", "w": 0.05})");
  SimulationOptions so;
  so.branch = Branch::retract;
  so.max_indentation = 2e-6;
  so.noise = 1e-5;
  const CurveData data = simulate_curve(truth, so);
  const FitSummary s = fit(data, truth, options({FitParameter::K, FitParameter::G, FitParameter::w,
                                                 FitParameter::delta0}));
  INFO(s.brief_report());
  CHECK_FALSE(s.identifiable);
  REQUIRE(s.unidentifiable.size() >= 1);
  CHECK(s.unidentifiable[0].find("G") != std::string::npos);
  CHECK(s.unidentifiable[0].find("delta0") != std::string::npos);
  CHECK(std::isnan(s[FitParameter::G].standard_error));
  CHECK(std::isnan(s[FitParameter::delta0].standard_error));
  CHECK(std::isfinite(s[FitParameter::K].standard_error));  // K and w stay determined
  CHECK(rel_err(s[FitParameter::K].value, 1e12) < 0.01);
  CHECK(s.identifiability_known);
  CHECK(s.brief_report().find("identifiable: no - the data cannot separate") != std::string::npos);
  CHECK_THAT(s[FitParameter::G].reason, Catch::Contains("not separable"));

  // With the contact point known, G is determined by the same data.
  const FitSummary fixed = fit(data, truth, options({FitParameter::K, FitParameter::G, FitParameter::w}));
  INFO(fixed.brief_report());
  CHECK(fixed.identifiable);
  CHECK(std::abs(fixed[FitParameter::G].value - 50) < 4 * fixed[FitParameter::G].standard_error);
}

TEST_CASE("the start does not depend on the scene's stiffness", "[fit][start]") {
  const Scene truth = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 2e-5},
      "medium": {"type": "half_space", "E": 3e4, "nu": 0.5}, "w": 0.001})");
  SimulationOptions so;
  so.max_indentation = 1e-6;
  so.noise = 1e-11;
  so.delta0 = -3e-6;
  const CurveData data = simulate_curve(truth, so);
  const auto o = options({FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0}, Branch::all);
  const FitSummary ref = fit(data, truth, o);
  for (double factor : {1e-6, 1e-3, 1e3, 1e6}) {
    Scene guess = truth;
    guess.medium.E *= factor;
    guess.w = 0.0;
    const FitSummary s = fit(data, guess, o);
    INFO("factor " << factor << "\n" << s.brief_report());
    CHECK(s.converged);
    CHECK(rel_err(s[FitParameter::E].value, ref[FitParameter::E].value) < 1e-6);
    CHECK(rel_err(s[FitParameter::w].value, ref[FitParameter::w].value) < 1e-5);
  }
}

TEST_CASE("robust losses resist outliers that bias least squares", "[fit][loss]") {
  const double E_star = 4e6 / 3.0, w = 0.02, R = 5e-5;
  CurveData c = jkr_half_space_retract(E_star, w, R, 0.0, 0.0, 1e-8, 3, 300);
  for (std::size_t i = 5; i < 300; i += 20) c.P[i] += 2e-6;  // 15 spikes
  const Scene scene = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 5e-5},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})");
  auto o = options({FitParameter::E, FitParameter::w, FitParameter::delta0});
  const FitSummary plain = fit(c, scene, o);
  o.loss = LossType::huber;
  o.loss_scale = 3e-8;
  const FitSummary huber = fit(c, scene, o);
  o.loss = LossType::cauchy;
  const FitSummary cauchy = fit(c, scene, o);
  INFO(plain.brief_report() << huber.brief_report() << cauchy.brief_report());
  const double E = E_star * 0.75;
  CHECK(rel_err(huber[FitParameter::E].value, E) < 0.3 * rel_err(plain[FitParameter::E].value, E));
  CHECK(rel_err(cauchy[FitParameter::E].value, E) < 0.3 * rel_err(plain[FitParameter::E].value, E));
  CHECK(rel_err(cauchy[FitParameter::w].value, w) < 0.02);
}

TEST_CASE("measured contact radii tighten the estimates", "[fit][radius]") {
  const Scene truth = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layer", "E": 1e6, "nu": 0.3, "h": 1e-5}, "model": "leading", "w": 0.05})");
  SimulationOptions so;
  so.branch = Branch::retract;
  so.max_indentation = 1e-6;
  so.noise = 2e-5;
  so.with_radius = true;
  const CurveData with_a = simulate_curve(truth, so);
  CurveData without_a = with_a;
  without_a.a.clear();
  const auto o = options({FitParameter::E, FitParameter::w, FitParameter::delta0});
  const FitSummary sa = fit(with_a, truth, o), s = fit(without_a, truth, o);
  INFO(sa.brief_report() << s.brief_report());
  CHECK(sa.converged);
  CHECK(std::abs(sa[FitParameter::E].value - 1e6) < 4 * sa[FitParameter::E].standard_error);
  CHECK(sa[FitParameter::w].standard_error < 0.5 * s[FitParameter::w].standard_error);
}

TEST_CASE("no adhesion in the data: w ends at its bound and says so", "[fit][w0]") {
  const Scene truth = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-4},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})");
  SimulationOptions so;
  so.branch = Branch::approach;
  so.max_indentation = 1e-6;
  const FitSummary s = fit(simulate_curve(truth, so), truth,
                           options({FitParameter::E, FitParameter::w, FitParameter::delta0}, Branch::approach));
  INFO(s.brief_report());
  CHECK(s[FitParameter::w].value < 1e-12);
  CHECK(s[FitParameter::w].at_bound);
  CHECK(std::isnan(s[FitParameter::w].standard_error));
  CHECK(rel_err(s[FitParameter::E].value, 1e6) < 1e-8);
}

TEST_CASE("data and parameters a fit cannot use are rejected with the reason", "[fit][errors]") {
  const Scene hs = scene_from(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.5}})");
  CurveData c;
  c.delta = {0, 1e-7, 2e-7, 3e-7};
  c.P = {0, 1e-9, 4e-9, 9e-9};
  auto msg = [&](const Scene& s, std::vector<FitParameter> free, const CurveData& d) {
    try {
      fit(d, s, options(std::move(free), Branch::all));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(msg(hs, {FitParameter::K}, c), Catch::Contains("K") && Catch::Contains("use E"));
  CHECK_THAT(msg(hs, {FitParameter::E, FitParameter::R}, c), Catch::Contains("paraboloid"));
  CHECK_THAT(msg(hs, {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0}, c),
             Catch::Contains("more samples than parameters"));
  CurveData flat = c;
  flat.P = {1, 1, 1, 1};
  CHECK_THAT(msg(hs, {FitParameter::E}, flat), Catch::Contains("P is constant"));
  CurveData falling = c;
  falling.P = {9e-9, 4e-9, 1e-9, 0};
  CHECK_THAT(msg(hs, {FitParameter::E, FitParameter::delta0}, falling), Catch::Contains("no contact region"));
  CurveData nan = c;
  nan.P[2] = std::nan("");
  CHECK_THAT(msg(hs, {FitParameter::E}, nan), Catch::Contains("row 3") && Catch::Contains("not finite"));
  const Scene layer = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layer", "E": 1e6, "nu": 0.3, "h": 1e-5}, "model": "two_term"})");
  CHECK_THAT(msg(layer, {FitParameter::E, FitParameter::K}, c), Catch::Contains("E and K/G"));
  FitOptions bad;
  bad.free = {FitParameter::E};
  bad.loss = LossType::huber;
  CHECK_THROWS_AS(fit(c, hs, bad), DomainError);
}
