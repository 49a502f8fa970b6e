// Fits across the JKR-DMT transition: the scene's adhesion model (jkr, dmt, maugis_dugdale)
// in the fit, sigma0 as a free parameter, and what a JKR fit of a Maugis-Dugdale curve costs.
//
// Oracles: the DMT curves are written here from the closed form (delta = a^2/R,
// P = 4 E* a^3/(3R) - 2 pi w R) or from the medium's non-adhesive states with the DMT force
// written out; the Maugis-Dugdale curves come from the library's closed form
// (maugis_dugdale.hpp, solved in double and checked against a 50-digit reference there),
// which shares no code path with the fit's Jet derivatives or its radius search.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include <boost/math/constants/constants.hpp>

#include "fit/evaluators/adhesive_curve.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/maugis_dugdale.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/simulate.hpp"
#include "support/cli_support.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
using test::rel_err;

namespace {

constexpr double kPi = boost::math::constants::pi<double>();

// An AFM tip on a stiff material (the issue's setting): R = 20 nm, E = 1 GPa, w = 0.05 J/m^2.
constexpr double kR = 20e-9, kE = 1e9, kNu = 0.3, kW = 0.05;
const double kEstar = kE / (1.0 - kNu * kNu);

Scene scene_from(const std::string& json) { return parse_scene(json, "test scene"); }

// The Dugdale stress that gives Maugis' lambda on the AFM half-space (maugis_lambda inverted:
// lambda is linear in sigma0).
double sigma0_for(double lambda) { return lambda / maugis_lambda(kR, kEstar, kW, 1.0); }

using StateAt = std::function<std::pair<double, double>(double)>;  // a -> (delta, P)

// A retract: n samples evenly in a from a_max down to the release radius a_release, then n/2
// samples free of contact (P = P0) below the release approach; noise is Gaussian on P.
CurveData retract_curve(const StateAt& state, double a_max, double a_release, double d0, double P0,
                        double noise, unsigned seed, std::size_t n = 300) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = a_max - (a_max - a_release) * i / (n - 1.0);
    const auto [delta, P] = state(a);
    c.delta.push_back(delta + d0);
    c.P.push_back(P + P0 + noise * g(rng));
    c.segment.push_back(1);
  }
  const double d_release = state(a_release).first, span = state(a_max).first - d_release;
  for (std::size_t i = 1; i <= n / 2; ++i) {
    c.delta.push_back(d_release - span * i / n + d0);
    c.P.push_back(P0 + noise * g(rng));
    c.segment.push_back(1);
  }
  return c;
}

// Maugis-Dugdale retract on the AFM half-space down to its load-controlled pull-off.
CurveData maugis_retract(double lambda, double noise, unsigned seed, double d0 = 0.0) {
  const double sigma0 = sigma0_for(lambda);
  const double length = std::cbrt(kPi * kW * kR * kR / (4.0 * kEstar / 3.0));
  const StateAt state = [&](double a) {
    const AdhesiveState s = maugis_dugdale_half_space(kR, kEstar, kW, sigma0, a);
    return std::make_pair(s.delta, s.P);
  };
  const double a_po = maugis_dugdale_pull_off(kR, kEstar, kW, sigma0).a;
  return retract_curve(state, a_po + 4.0 * length, a_po, d0, 0.0, noise, seed);
}

FitOptions retract_options(std::vector<FitParameter> free) {
  FitOptions o;
  o.free = std::move(free);
  o.branch = Branch::retract;
  return o;
}

std::string afm_scene(const std::string& adhesion, double E = kE) {
  return R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "half_space", "E": )" +
         std::to_string(E) + R"(, "nu": 0.3}, "adhesion": )" + adhesion + "}";
}

}  // namespace

TEST_CASE("the fit's Maugis-Dugdale point and its Jet derivatives against the closed form", "[fit][adhesion]") {
  // Values against maugis_dugdale_half_space (double, TOMS 748 on m); derivatives in E*, w, R,
  // sigma0 and a against central differences of it (step 1e-5 relative: truncation ~1e-10,
  // rounding ~1e-11 / 1e-5).
  using J = detail::Jet8;  // slots 0-4: E*, w, R, sigma0, a
  for (const double lambda : {0.01, 0.1, 1.0, 5.0, 100.0}) {
    const double sigma0 = sigma0_for(lambda);
    for (const double a_po_factor : {0.05, 1.0, 4.0}) {
      const double a = a_po_factor * maugis_dugdale_pull_off(kR, kEstar, kW, sigma0).a + 1e-10;
      const double x[5] = {kEstar, kW, kR, sigma0, a};
      J delta, P;
      detail::maugis_curve(J(a, 4), J(kEstar, 0), J(kW, 1), J(kR, 2), J(sigma0, 3), &delta, &P);
      const AdhesiveState ref = maugis_dugdale_half_space(kR, kEstar, kW, sigma0, a);
      INFO("lambda = " << lambda << ", a = " << a);
      CHECK(rel_err(P.a, ref.P) < 1e-12);
      CHECK(rel_err(delta.a, ref.delta) < 1e-12);
      for (int k = 0; k < 5; ++k) {
        double lo[5], hi[5];
        std::copy(x, x + 5, lo);
        std::copy(x, x + 5, hi);
        const double h = 1e-5 * x[k];
        lo[k] -= h;
        hi[k] += h;
        const AdhesiveState m = maugis_dugdale_half_space(lo[2], lo[0], lo[1], lo[3], lo[4]);
        const AdhesiveState p = maugis_dugdale_half_space(hi[2], hi[0], hi[1], hi[3], hi[4]);
        INFO("parameter " << k);
        // Scaled by the value: a derivative near zero is compared at the value's size.
        CHECK(std::abs(P.v[k] - (p.P - m.P) / (2 * h)) * x[k] < 1e-7 * std::abs(ref.P));
        CHECK(std::abs(delta.v[k] - (p.delta - m.delta) / (2 * h)) * x[k] < 1e-7 * std::abs(ref.delta));
      }
    }
  }
}

TEST_CASE("DMT on a half-space: closed-form curves fitted back to E and w", "[fit][adhesion]") {
  const double d0 = 3e-9, P0 = 2e-9;
  // Classical DMT: delta = a^2/R, P = 4 E* a^3/(3R) - 2 pi w R, pulling off at a = 0.
  const StateAt dmt = [&](double a) {
    return std::make_pair(a * a / kR, 4.0 * kEstar * a * a * a / (3.0 * kR) - 2.0 * kPi * kW * kR);
  };
  const CurveData c = retract_curve(dmt, 15e-9, 0.0, d0, P0, 0.0, 1);
  const Scene scene = scene_from(afm_scene(R"({"model": "dmt"})", 3e8));  // E 3x off, w absent
  const FitSummary s = fit(c, scene, retract_options({FitParameter::E, FitParameter::w, FitParameter::delta0,
                                                      FitParameter::P0}));
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(s.model == "dmt on half_space");
  CHECK(s.family == FitFamily::hertz);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-6);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-6);
  CHECK(std::abs(s[FitParameter::delta0].value - d0) < 1e-6 * d0);
  CHECK(s.identifiable);
  // The pull-off is at a = 0: the deepest force is the DMT one, 2 pi w R.
  CHECK(rel_err(-s.pull_off_force, 2.0 * kPi * kW * kR) < 1e-6);
}

TEST_CASE("DMT on a layer (tabulated exact model): fitted back to E and w", "[fit][adhesion]") {
  const std::string json = R"({"indenter": {"shape": "paraboloid", "R": 1e-6},
      "medium": {"type": "layer", "E": 5e6, "nu": 0.45, "h": 2e-7}, "model": "exact", "w": 0.02,
      "adhesion": {"model": "dmt"}})";
  const Scene truth = scene_from(json);
  const double R = 1e-6, w = 0.02, d0 = 5e-8;
  // The medium's own non-adhesive states (the exact layer), the DMT force written out here.
  const BuiltScene built = build_scene(truth);
  const StateAt dmt = [&](double a) {
    const NonAdhesiveState h = built.model->state(a);
    return std::make_pair(h.delta_H, h.P_H - 2.0 * kPi * w * R);
  };
  const CurveData c = retract_curve(dmt, 3e-7, 1e-10, d0, 0.0, 0.0, 1);
  Scene guess = truth;
  guess.w = 0.0;
  guess.medium.E *= 4.0;
  FitOptions o = retract_options({FitParameter::E, FitParameter::w, FitParameter::delta0});
  o.table_points_per_decade = 160;
  const FitSummary s = fit(c, guess, o);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(s.family == FitFamily::tabulated);
  CHECK(s.model.rfind("dmt on ", 0) == 0);
  CHECK(rel_err(s[FitParameter::E].value, 5e6) < 1e-6);
  CHECK(rel_err(s[FitParameter::w].value, w) < 1e-6);
  CHECK(std::abs(s[FitParameter::delta0].value - d0) < 1e-6 * d0);
}

TEST_CASE("DMT on a Winkler foundation: the closed-form inverse without the JKR root", "[fit][adhesion]") {
  // p = K (delta - r^2/(2R)) on r < a: delta_H = a^2/(2R), P_H = pi K a^4/(4R); DMT subtracts
  // 2 pi w R. The foundation family inverts delta(a) in closed form (FoundationCurve::invert).
  const double K = 1e12, R = 1e-4, w = 0.03, d0 = 1e-7;
  const StateAt dmt = [&](double a) {
    return std::make_pair(a * a / (2.0 * R), kPi * K * a * a * a * a / (4.0 * R) - 2.0 * kPi * w * R);
  };
  const CurveData c = retract_curve(dmt, 2e-5, 0.0, d0, 0.0, 0.0, 1);
  const Scene scene = scene_from(R"({"indenter": {"shape": "paraboloid", "R": 1e-4}, "medium": {"type": "winkler",
      "K": 3e11}, "adhesion": {"model": "dmt"}})");
  const FitSummary s = fit(c, scene, retract_options({FitParameter::K, FitParameter::w, FitParameter::delta0}));
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(s.model == "dmt on winkler");
  CHECK(rel_err(s[FitParameter::K].value, K) < 1e-6);
  CHECK(rel_err(s[FitParameter::w].value, w) < 1e-6);
  CHECK(std::abs(s[FitParameter::delta0].value - d0) < 1e-6 * d0);
}

TEST_CASE("Maugis-Dugdale on the half-space: E, w and sigma0 fitted back at lambda 0.1, 1, 5", "[fit][adhesion]") {
  for (const double lambda : {0.1, 1.0, 5.0}) {
    DYNAMIC_SECTION("lambda = " << lambda) {
      const double sigma0 = sigma0_for(lambda);
      // Start: E 2x, sigma0 3x off, w from the pull-off (find_start).
      const Scene scene = scene_from(afm_scene(R"({"model": "maugis_dugdale", "sigma0": )" +
                                               std::to_string(3.0 * sigma0) + "}", 2.0 * kE));
      const FitOptions o = retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0});
      SECTION("noise-free: to 1e-6") {
        const FitSummary s = fit(maugis_retract(lambda, 0.0, 1), scene, o);
        INFO(s.brief_report());
        CHECK(s.converged);
        CHECK(s.model == "maugis_dugdale on half_space");
        CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-6);
        CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-6);
        CHECK(rel_err(s[FitParameter::sigma0].value, sigma0) < 1e-6);
      }
      // 0.1 % of the pull-off: at 1 % the curve at lambda = 5 no longer excludes JKR (the
      // study in docs/fitting.md), and sigma0 is then reported without an error bar.
      SECTION("0.1 % noise: within 3 standard errors") {
        const double noise = 0.001 * 2.0 * kPi * kW * kR;
        const FitSummary s = fit(maugis_retract(lambda, noise, 7), scene, o);
        INFO(s.brief_report());
        CHECK(s.converged);
        CHECK(s.identifiable);
        for (const auto& [q, truth] : {std::pair{FitParameter::E, kE}, std::pair{FitParameter::w, kW},
                                       std::pair{FitParameter::sigma0, sigma0}}) {
          INFO(to_string(q));
          const ParameterEstimate& e = s[q];
          REQUIRE(std::isfinite(e.standard_error));
          CHECK(std::abs(e.value - truth) < 3.0 * e.standard_error);
        }
      }
    }
  }
}

TEST_CASE("Maugis-Dugdale on approach and retract: the approach snaps in at zero load", "[fit][adhesion]") {
  const double lambda = 1.0, sigma0 = sigma0_for(lambda), d0 = 2e-9;
  const auto state = [&](double a) { return maugis_dugdale_half_space(kR, kEstar, kW, sigma0, a); };
  // The zero-load radius by bisection on the closed form (P < 0 below it).
  double lo = 1e-12, hi = 30e-9;
  for (int i = 0; i < 200; ++i) (state(0.5 * (lo + hi)).P < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double a0 = 0.5 * (lo + hi), a_max = 20e-9;
  CurveData c;
  const double d_zero = state(a0).delta;
  for (int i = 1; i <= 100; ++i) {  // free before contact
    c.delta.push_back(d_zero - 10e-9 * (101 - i) / 100.0 + d0);
    c.P.push_back(0.0);
    c.segment.push_back(0);
  }
  for (int i = 0; i < 200; ++i) {
    const AdhesiveState st = state(a0 + (a_max - a0) * i / 199.0);
    c.delta.push_back(st.delta + d0);
    c.P.push_back(st.P);
    c.segment.push_back(0);
  }
  const CurveData retract = maugis_retract(lambda, 0.0, 1, d0);
  for (std::size_t i = 0; i < retract.delta.size(); ++i) {
    c.delta.push_back(retract.delta[i]);
    c.P.push_back(retract.P[i]);
    c.segment.push_back(1);
  }
  const Scene scene = scene_from(afm_scene(R"({"model": "maugis_dugdale", "sigma0": )" +
                                           std::to_string(2.0 * sigma0) + "}", 2.0 * kE));
  FitOptions o = retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0, FitParameter::delta0});
  o.branch = Branch::all;
  const FitSummary s = fit(c, scene, o);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-6);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-6);
  CHECK(rel_err(s[FitParameter::sigma0].value, sigma0) < 1e-6);
  CHECK(std::abs(s[FitParameter::delta0].value - d0) < 1e-6 * d0);
}

TEST_CASE("a JKR fit of a Maugis-Dugdale curve: the bias towards DMT's 4/3", "[fit][adhesion]") {
  // At small lambda the pull-off is near 2 pi w R; JKR reads it as 1.5 pi w_JKR R, so
  // w_JKR -> 4/3 w as lambda -> 0. Measured (docs/fitting.md): the ratio at each lambda.
  const Scene jkr = scene_from(afm_scene(R"({"model": "jkr"})", 2.0 * kE));
  const FitOptions o = retract_options({FitParameter::E, FitParameter::w});
  double previous = 0.0;
  for (const double lambda : {0.1, 1.0, 5.0}) {
    const FitSummary s = fit(maugis_retract(lambda, 0.0, 1), jkr, o);
    INFO("lambda = " << lambda << "\n" << s.brief_report());
    const double ratio = s[FitParameter::w].value / kW;
    // Between the DMT limit and JKR, falling towards 1 as lambda grows.
    CHECK(ratio < 4.0 / 3.0 + 0.01);
    CHECK(ratio > 0.95);
    if (previous > 0.0) CHECK(ratio < previous);
    previous = ratio;
    if (lambda == 0.1) CHECK(ratio > 1.2);
  }
}

TEST_CASE("sigma0 is reported not identifiable where Maugis-Dugdale is JKR", "[fit][adhesion][identifiability]") {
  // lambda = 300: the Dugdale zone is a sliver at the edge; the curve does not depend on sigma0
  // beyond the noise.
  const double lambda = 300.0;
  const double noise = 0.01 * 2.0 * kPi * kW * kR;
  const Scene scene = scene_from(afm_scene(R"({"model": "maugis_dugdale", "sigma0": )" +
                                           std::to_string(sigma0_for(lambda)) + "}"));
  const FitSummary s = fit(maugis_retract(lambda, noise, 3), scene,
                           retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0}));
  INFO(s.brief_report());
  CHECK_FALSE(s.identifiable);
  CHECK_FALSE(s[FitParameter::sigma0].identifiable);
  CHECK_FALSE(s[FitParameter::sigma0].reason.empty());
  CHECK_THAT(s.identifiability(), Catch::StartsWith("no: "));
  CHECK_THAT(s.identifiability(), Catch::Contains("sigma0"));
  CHECK_THAT(s.identifiability(), Catch::Contains("JKR limit"));
  // E and w keep their error bars (from the fit with sigma0 held where it stopped, or at the
  // solution when only the limit test failed), and they cover the truth.
  for (const auto& [q, truth] : {std::pair{FitParameter::E, kE}, std::pair{FitParameter::w, kW}}) {
    INFO(to_string(q));
    REQUIRE(std::isfinite(s[q].standard_error));
    CHECK(std::abs(s[q].value - truth) < 3.0 * s[q].standard_error);
  }
}

TEST_CASE("a sigma0 that runs to the JKR limit is held there, and E and w keep their error bars",
          "[fit][adhesion][identifiability]") {
  // lambda = 5 at 1 % noise: in seed 5 the solver takes sigma0 to the closed form's bound
  // (lambda ~ 1e4), where the covariance of all three fails.
  const double noise = 0.01 * std::abs(maugis_dugdale_pull_off(kR, kEstar, kW, sigma0_for(5.0)).P);
  const Scene scene = scene_from(afm_scene(R"({"model": "maugis_dugdale", "sigma0": )" +
                                           std::to_string(2.0 * sigma0_for(5.0)) + "}", 2.0 * kE));
  const FitSummary s = fit(maugis_retract(5.0, noise, 5), scene,
                           retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0}));
  INFO(s.brief_report());
  REQUIRE(s[FitParameter::sigma0].value > 100.0 * sigma0_for(5.0));  // it did run away
  CHECK_FALSE(s[FitParameter::sigma0].identifiable);
  CHECK(std::isnan(s[FitParameter::sigma0].standard_error));
  CHECK_THAT(s[FitParameter::sigma0].reason, Catch::Contains("JKR limit") && Catch::Contains("ran to lambda"));
  CHECK(s.identifiability_known);
  CHECK(std::isfinite(s[FitParameter::E].standard_error));
  CHECK(std::isfinite(s[FitParameter::w].standard_error));
  CHECK(std::abs(s[FitParameter::E].value - kE) < 3.0 * s[FitParameter::E].standard_error);
  bool warned = false;
  for (const auto& line : s.warnings) warned = warned || line.find("sigma0 ran to the JKR limit") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("bad adhesion combinations in a fit are refused with one clear message", "[fit][adhesion]") {
  const CurveData c = maugis_retract(1.0, 0.0, 1);
  auto message = [&](const std::string& json, std::vector<FitParameter> free) {
    try {
      fit(c, scene_from(json), retract_options(std::move(free)));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::vector<FitParameter> E_w_sigma0{FitParameter::E, FitParameter::w, FitParameter::sigma0};
  // sigma0 free without a Dugdale law.
  CHECK_THAT(message(afm_scene(R"({"model": "jkr"})"), E_w_sigma0),
             Catch::Contains("sigma0") && Catch::Contains("'jkr'") && Catch::Contains("maugis_dugdale"));
  CHECK_THAT(message(afm_scene(R"({"model": "dmt"})"), E_w_sigma0), Catch::Contains("'dmt'"));
  // Maugis-Dugdale on a thin-layer law, which gives no gap outside the contact (more in
  // test_fit_dugdale.cpp, where layers, stacks and other profiles are fitted).
  CHECK_THAT(message(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "layer", "E": 1e9,
      "nu": 0.3, "h": 1e-8}, "model": "uniform", "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})",
                     {FitParameter::E, FitParameter::w}),
             Catch::Contains("maugis_dugdale") && Catch::Contains("'uniform'") && Catch::Contains("'jkr'"));
  // A cone has no tip radius for the classical DMT.
  CHECK_THAT(message(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70}, "medium": {"type": "half_space",
      "E": 1e9, "nu": 0.3}, "adhesion": {"model": "dmt"}})", {FitParameter::E, FitParameter::w}),
             Catch::Contains("radius of curvature"));
}

TEST_CASE("simulate_curve follows the scene's adhesion model", "[fit][adhesion]") {
  // It used the JKR law whatever the scene said. The deepest retract force is each model's
  // pull-off: DMT's -2 pi w R (at a = 0, so exactly a sample), Maugis-Dugdale's closed form
  // (flat there: the nearest of samples 19 pm apart is within 1e-3), never JKR's -1.5 pi w R.
  SimulationOptions so;
  so.branch = Branch::retract;
  so.points_per_branch = 400;
  so.max_indentation = 5e-9;
  auto deepest = [&](const std::string& adhesion) {
    Scene s = scene_from(afm_scene(adhesion));
    s.w = kW;
    const CurveData c = simulate_curve(s, so);
    return *std::min_element(c.P.begin(), c.P.end());
  };
  CHECK(rel_err(deepest(R"({"model": "dmt"})"), -2.0 * kPi * kW * kR) < 1e-9);
  const double sigma0 = sigma0_for(1.0);
  const double md = maugis_dugdale_pull_off(kR, kEstar, kW, sigma0).P;
  CHECK(rel_err(deepest(R"({"model": "maugis_dugdale", "sigma0": )" + std::to_string(sigma0) + "}"), md) < 2e-3);
  CHECK(rel_err(deepest(R"({"model": "jkr"})"), -1.5 * kPi * kW * kR) < 2e-3);
  CHECK(rel_err(md, -1.5 * kPi * kW * kR) > 0.05);
}

TEST_CASE("Maugis-Dugdale with a spacing z0: sigma0 follows w in the fit", "[fit][adhesion]") {
  // sigma0 = 16 w / (9 sqrt 3 z0) with z0 = 0.3 nm: lambda from the curve's own w.
  const double z0 = 0.3e-9;
  const double sigma0 = lennard_jones_dugdale_stress(kW, z0);
  const double lambda = maugis_lambda(kR, kEstar, kW, sigma0);
  const Scene scene = scene_from(afm_scene(R"({"model": "maugis_dugdale", "z0": 3e-10})", 2.0 * kE));
  const FitSummary s = fit(maugis_retract(lambda, 0.0, 1), scene, retract_options({FitParameter::E, FitParameter::w}));
  INFO("lambda = " << lambda << "\n" << s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-6);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-6);
}

TEST_CASE("CLI: fit --free E,w,sigma0 on a Maugis-Dugdale scene, and bad combinations exit 2 with one line",
          "[fit][adhesion][cli]") {
  namespace cli = test::cli;
  const double lambda = 1.0, sigma0 = sigma0_for(lambda);
  const CurveData c = maugis_retract(lambda, 0.0, 1);
  std::ostringstream csv;
  csv.precision(17);
  csv << "delta,P,segment\n";
  for (std::size_t i = 0; i < c.delta.size(); ++i) csv << c.delta[i] << "," << c.P[i] << "," << c.segment[i] << "\n";
  const std::string curve = cli::write_file("md_curve.csv", csv.str());
  const std::string md = cli::write_file("md.json", afm_scene(R"({"model": "maugis_dugdale", "sigma0": )" +
                                                              std::to_string(2.0 * sigma0) + "}", 2.0 * kE));
  const std::string report = cli::unique("md_report.json");
  const cli::Run r = cli::run("fit " + curve + " --scene " + md + " --branch retract --free E,w,sigma0 --out " + report);
  INFO(r.err << r.out);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(cli::slurp(report));
  const auto& p = j["parameters"];
  CHECK(rel_err(p["E"]["value"].get<double>(), kE) < 1e-6);
  CHECK(rel_err(p["w"]["value"].get<double>(), kW) < 1e-6);
  CHECK(rel_err(p["sigma0"]["value"].get<double>(), sigma0) < 1e-6);
  CHECK(j["identifiable"] == true);
  CHECK(r.out.find("sigma0") != std::string::npos);

  auto one_line_exit_2 = [&](const std::string& scene_json, const std::string& free, const std::string& needle) {
    const std::string scene = cli::write_file("bad.json", scene_json);
    const cli::Run bad = cli::run("fit " + curve + " --scene " + scene + " --branch retract --free " + free);
    INFO(bad.err);
    CHECK(bad.code == 2);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
    CHECK(bad.err.find(needle) != std::string::npos);
  };
  one_line_exit_2(afm_scene(R"({"model": "jkr"})"), "E,w,sigma0", "sigma0");
  one_line_exit_2(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "layer", "E": 1e9, "nu": 0.3,
      "h": 1e-8}, "model": "uniform", "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})", "E,w", "maugis_dugdale");
  one_line_exit_2(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70}, "medium": {"type": "half_space", "E": 1e9,
      "nu": 0.3}, "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})", "E,w,sigma0", "radius of curvature");
  std::remove(report.c_str());
}
