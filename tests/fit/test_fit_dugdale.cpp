// Fits of a Dugdale law solved on the medium (the "dugdale" family, src/fit/evaluators/dugdale_curve.cpp):
// Maugis-Dugdale and the Dugdale DMT on exact layers, a stack and a half-space with a sphere.
//
// Oracles: the curves are the library's adhesive laws (make_adhesive_law, the Dugdale solver
// at each sample's own radius, checked against Maugis' closed form and the limits in
// tests/adhesion/test_dugdale_solver.cpp); the fit instead interpolates a grid of radii, scales
// one solver built at the scene's modulus to the fitted E, differentiates by forward
// differences and starts from the JKR curve of the medium - none of which the curves share.
// The scaling itself is checked against a solver built at the other modulus.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "adhesion/dugdale_solver.hpp"
#include "fit/evaluators/fit_model.hpp"
#include "layerjkr/adhesion.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
using test::rel_err;

namespace {

// The issue's AFM case: a 20 nm tip on a 10 nm, 3 GPa film on a rigid base, w = 0.05 J/m^2,
// sigma0 = 170 MPa (Lennard-Jones with z0 = 0.3 nm): lambda ~ 0.5, between JKR and DMT.
constexpr double kE = 3e9, kW = 0.05, kSigma0 = 1.7e8;

std::string film_scene(const std::string& adhesion, double E = kE, const std::string& medium = "") {
  const std::string m = medium.empty() ? R"({"type": "layer", "E": )" + std::to_string(E) +
                                             R"(, "nu": 0.3, "h": 1e-8})"
                                       : medium;
  return R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": )" + m +
         R"(, "model": "exact", "w": 0.05, "adhesion": )" + adhesion + "}";
}

Scene scene_from(const std::string& json) { return parse_scene(json, "test scene"); }

AdhesiveLawPtr law_of(const Scene& scene) {
  const BuiltScene built = build_scene(scene, 0.0, false);
  return make_adhesive_law(built.model, resolve_model(scene).spec, scene.w, scene.adhesion);
}

// A retract written from the law: n samples evenly in a from a_release + span_a down to the
// law's load-controlled pull-off (a = 0 for the DMT), then n/2 samples free of contact.
CurveData retract_from(const AdhesiveLawPtr& law, double span_a, double noise, unsigned seed, int n = 60) {
  const AdhesiveSolution solution(law);
  const std::optional<CriticalPoint> po = solution.pull_off();
  const double a_release = po ? po->a : 0.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  for (int i = 0; i < n; ++i) {
    const AdhesiveState s = law->at(a_release + span_a * (n - 1 - i) / (n - 1.0));
    c.delta.push_back(s.delta);
    c.P.push_back(s.P + noise * g(rng));
    c.segment.push_back(1);
  }
  const double d_release = c.delta.back(), span = c.delta.front() - d_release;
  for (int i = 1; i <= n / 2; ++i) {
    c.delta.push_back(d_release - span * i / n);
    c.P.push_back(noise * g(rng));
    c.segment.push_back(1);
  }
  return c;
}

FitOptions retract_options(std::vector<FitParameter> free) {
  FitOptions o;
  o.free = std::move(free);
  o.branch = Branch::retract;
  return o;
}

std::string sigma0_adhesion(const char* model, double sigma0) {
  return std::string(R"({"model": ")") + model + R"(", "sigma0": )" + std::to_string(sigma0) + "}";
}

}  // namespace

TEST_CASE("the Dugdale family scales one solver to any E and differentiates it", "[fit][adhesion][dugdale]") {
  // The family is built at E_ref = 3 GPa; evaluated at E = 6 GPa it must give the law of a film
  // built at 6 GPa (P(a; E, w, s0) = k P(a; E_ref, w/k, s0/k), k = E/E_ref), and its Jet
  // derivatives in E, w and sigma0 must match central differences of such laws.
  const Scene scene = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0)));
  detail::SceneParameters fixed;
  const auto model = detail::make_curve_model(scene, resolve_model(scene), FitOptions{}, 8e-9, &fixed);
  CHECK(model->family() == FitFamily::dugdale);
  CHECK(model->model_name() == "maugis_dugdale on exact");
  REQUIRE(model->start_model() != nullptr);
  CHECK(model->start_model()->family() == FitFamily::tabulated);
  const double E = 2.0 * kE, w = 0.8 * kW, sigma0 = 1.3 * kSigma0;
  auto law_at = [&](double E_, double w_, double s_) {
    Scene s = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", s_), E_));
    s.w = w_;
    return law_of(s);
  };
  using J = detail::Jet4;  // slots 0-2: E, w, sigma0; 3: a
  detail::CurveParameters<J> p;
  p.E = J(E, 0);
  p.s = sqrt(J(w, 1));
  p.sigma0 = J(sigma0, 2);
  const AdhesiveLawPtr truth = law_at(E, w, sigma0);
  const double x[3] = {E, w, sigma0};
  for (const double a : {0.0, 2e-9, 7e-9, 1.5e-8}) {
    J delta, P;
    model->evaluate(J(a, 3), p, &delta, &P);
    const AdhesiveState ref = truth->at(a);
    INFO("a = " << a);
    // The grid's interpolation error (the family's note) is ~1e-8 of the spans.
    CHECK(std::abs(P.a - ref.P) < 1e-7 * 4e-6);
    CHECK(std::abs(delta.a - ref.delta) < 1e-7 * 1.6e-8);
    for (int k = 0; k < 3; ++k) {
      double lo[3] = {E, w, sigma0}, hi[3] = {E, w, sigma0};
      const double h = 1e-4 * x[k];
      lo[k] -= h;
      hi[k] += h;
      const AdhesiveState m = law_at(lo[0], lo[1], lo[2])->at(a), q = law_at(hi[0], hi[1], hi[2])->at(a);
      // Per unit relative change x d/dx. Inside, w and sigma0 are forward differences of step
      // 1e-3 (truncation ~5e-4 of the derivative), and E reaches them through the scaling;
      // here central differences of step 1e-4 (truncation ~1e-8).
      const double dP = P.v[k] * x[k], dP_ref = (q.P - m.P) / (2 * h) * x[k];
      const double dd = delta.v[k] * x[k], dd_ref = (q.delta - m.delta) / (2 * h) * x[k];
      INFO("parameter " << k << ": x dP/dx " << dP << " vs " << dP_ref << ", x d delta/dx " << dd << " vs " << dd_ref);
      CHECK(std::abs(dP - dP_ref) < 2e-3 * std::abs(dP_ref) + 1e-7 * 4e-6);
      CHECK(std::abs(dd - dd_ref) < 2e-3 * std::abs(dd_ref) + 1e-7 * 1.6e-8);
    }
  }
}

TEST_CASE("the Dugdale family's grid refines until its interpolation error meets the target",
          "[fit][adhesion][dugdale]") {
  // Towards JKR (here lambda ~ 4 on a 1 GPa film) the curve turns from the adhesive disc's to
  // JKR's within a few narrow zone widths: 31 radii leave ~1e-4 of the spans, so the grid
  // doubles its intervals. Checked against the law at radii off the grid.
  const Scene scene = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", 5.1e8), 1e9));
  detail::SceneParameters fixed;
  const auto model = detail::make_curve_model(scene, resolve_model(scene), FitOptions{}, 8e-9, &fixed);
  REQUIRE(model->notes().size() == 1);
  const std::string note = model->notes()[0];
  INFO(note);
  CHECK_THAT(note, Catch::Contains("on 61 radii") || Catch::Contains("on 121 radii"));
  const double error = std::stod(note.substr(note.find("interpolation error ") + 20));
  CHECK(error < 1e-6);
  const AdhesiveLawPtr law = law_of(scene);
  detail::CurveParameters<detail::Jet1> p;
  p.E = detail::Jet1(1e9);
  p.s = detail::Jet1(std::sqrt(kW));
  p.sigma0 = detail::Jet1(5.1e8);
  double P_span = 0.0;
  for (int k = 0; k <= 40; ++k) P_span = std::max(P_span, std::abs(law->at(model->max_radius() * k / 40.0).P));
  for (const double a : {0.37e-9, 1.3e-9, 2.9e-9, 4.1e-9, 7.7e-9}) {
    detail::Jet1 delta, P;
    model->evaluate(detail::Jet1(a, 0), p, &delta, &P);
    INFO("a = " << a);
    CHECK(std::abs(P.a - law->at(a).P) < 1e-6 * P_span);
  }
  // At parameters where the grid meets its target nothing is added at the solution.
  detail::CurveParameters<double> at_scene{0.0, 0.0, 1e9, std::sqrt(kW), 0.0, 5.1e8};
  CHECK(model->notes_at(at_scene).empty());
}

TEST_CASE("Maugis-Dugdale on a film: E, w and sigma0 fitted back from the solver's own curve",
          "[fit][adhesion][dugdale]") {
  const Scene truth = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0)));
  const CurveData c = retract_from(law_of(truth), 15e-9, 0.0, 1);
  // Start: E and sigma0 2x off, w from the pull-off of the film's JKR curve (the start model).
  const Scene guess = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", 2.0 * kSigma0), 2.0 * kE));
  const FitSummary s = fit(c, guess, retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0}));
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(s.model == "maugis_dugdale on exact");
  CHECK(s.family == FitFamily::dugdale);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-5);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-5);
  CHECK(rel_err(s[FitParameter::sigma0].value, kSigma0) < 1e-5);
  CHECK(s.identifiable);
  // An interpolation error of ~1e-8 of the spans is far below any noise: stated, not warned.
  bool noted = false;
  for (const auto& line : s.notices) noted = noted || line.find("interpolation error") != std::string::npos;
  CHECK(noted);
  CHECK(s.warnings.empty());
}

TEST_CASE("Maugis-Dugdale on a film: the fit from the Dugdale table recovers a curve the direct solver wrote",
          "[fit][adhesion][dugdale]") {
  // Issue 35: the fit's states come from the medium's Dugdale table; the curve here is solved
  // directly at every sample's radius (DugdaleSolver without the table, which shares nothing
  // with it but the kernel), so the fitted values' distance to the truth is the table's error
  // seen through the fit (the direct solver's own fit agreed with the truth to 1e-5 before).
  const ElasticLayer film{kE, 0.3, 1e-8, Base::bonded};
  const detail::DugdaleSolver direct(make_paraboloid(2e-8), std::make_shared<ExactLayerKernel>(film, ExactLayerOptions{}));
  REQUIRE_FALSE(direct.tabulated());
  const Scene truth = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0)));
  const double a_release = AdhesiveSolution(law_of(truth)).pull_off()->a;
  CurveData c;
  const int n = 40;
  for (int i = 0; i < n; ++i) {
    const AdhesiveState st = direct.maugis_dugdale(a_release + 15e-9 * (n - 1 - i) / (n - 1.0), kW, kSigma0);
    c.delta.push_back(st.delta);
    c.P.push_back(st.P);
    c.segment.push_back(1);
  }
  for (int i = 1; i <= n / 2; ++i) {
    c.delta.push_back(c.delta[n - 1] - 2e-9 * i);
    c.P.push_back(0.0);
    c.segment.push_back(1);
  }
  const Scene guess = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", 2.0 * kSigma0), 2.0 * kE));
  const FitSummary s = fit(c, guess, retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0}));
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-4);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-4);
  CHECK(rel_err(s[FitParameter::sigma0].value, kSigma0) < 1e-4);  // measured 6.1e-5 (E 4.6e-8, w 4.8e-6)
  bool stated = false;
  for (const auto& line : s.notices) stated = stated || line.find("Dugdale table, measured error") != std::string::npos;
  CHECK(stated);
}

TEST_CASE("Maugis-Dugdale on a film with noise: E and w within 3 standard errors, and JKR's bias",
          "[fit][adhesion][dugdale]") {
  const Scene truth = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0)));
  const AdhesiveLawPtr law = law_of(truth);
  const double noise = 0.005 * 5.3e-9;  // 0.5 % of the pull-off force
  const CurveData c = retract_from(law, 15e-9, noise, 11);
  const FitSummary s = fit(c, scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0), 2.0 * kE)),
                           retract_options({FitParameter::E, FitParameter::w, FitParameter::delta0}));
  INFO(s.brief_report());
  CHECK(s.converged);
  for (const auto& [q, value] : {std::pair{FitParameter::E, kE}, std::pair{FitParameter::w, kW}}) {
    INFO(to_string(q));
    REQUIRE(std::isfinite(s[q].standard_error));
    CHECK(std::abs(s[q].value - value) < 3.0 * s[q].standard_error);
  }
  // The same curve read as JKR on the same film: w too high (towards DMT's 4/3), as the
  // adhesion check on the film warns (lambda ~ 0.5).
  const FitSummary jkr = fit(c, scene_from(film_scene(R"({"model": "jkr"})", 2.0 * kE)),
                             retract_options({FitParameter::E, FitParameter::w, FitParameter::delta0}));
  INFO(jkr.brief_report());
  CHECK(jkr[FitParameter::w].value > kW + 5.0 * jkr[FitParameter::w].standard_error);
}

TEST_CASE("the Dugdale DMT on a film and Maugis-Dugdale on a stack: fitted back", "[fit][adhesion][dugdale]") {
  SECTION("dmt with sigma0 on the film: E and w") {
    const Scene truth = scene_from(film_scene(sigma0_adhesion("dmt", kSigma0)));
    const CurveData c = retract_from(law_of(truth), 15e-9, 0.0, 1);
    const FitSummary s = fit(c, scene_from(film_scene(sigma0_adhesion("dmt", kSigma0), 2.0 * kE)),
                             retract_options({FitParameter::E, FitParameter::w}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(s.model == "dmt (Dugdale) on exact");
    CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-5);
    CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-5);
  }
  SECTION("maugis_dugdale with z0 on the film, the scene without w: sigma0 follows w from 0") {
    const Scene truth = scene_from(film_scene(R"({"model": "maugis_dugdale", "z0": 3e-10})"));
    const CurveData c = retract_from(law_of(truth), 15e-9, 0.0, 1, 40);
    Scene guess = scene_from(film_scene(R"({"model": "maugis_dugdale", "z0": 3e-10})", 2.0 * kE));
    guess.w = 0.0;  // the grid is first built for the non-adhesive curve
    const FitSummary s = fit(c, guess, retract_options({FitParameter::E, FitParameter::w}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-5);
    CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-5);
  }
  SECTION("maugis_dugdale on a film over a softer layer on a rigid base: E (scaling both) and w") {
    const std::string stack = R"({"type": "layers", "layers": [{"E": 3e9, "nu": 0.3, "h": 1e-8},
        {"E": 1e9, "nu": 0.4, "h": 2e-8}], "base": "bonded"})";
    const Scene truth = scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0), kE, stack));
    const CurveData c = retract_from(law_of(truth), 15e-9, 0.0, 1, 40);
    const std::string soft = R"({"type": "layers", "layers": [{"E": 6e9, "nu": 0.3, "h": 1e-8},
        {"E": 2e9, "nu": 0.4, "h": 2e-8}], "base": "bonded"})";
    const FitSummary s = fit(c, scene_from(film_scene(sigma0_adhesion("maugis_dugdale", kSigma0), kE, soft)),
                             retract_options({FitParameter::E, FitParameter::w}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-5);
    CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-5);
  }
  SECTION("maugis_dugdale on a half-space with a sphere (the solver's general path): E, w and sigma0") {
    const std::string json = R"({"indenter": {"shape": "sphere", "R": 1e-7}, "medium": {"type": "half_space",
        "E": 1e9, "nu": 0.3}, "w": 0.05, "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})";
    const Scene truth = scene_from(json);
    const CurveData c = retract_from(law_of(truth), 8e-9, 0.0, 1);
    Scene guess = truth;
    guess.medium.E = 2e9;
    guess.adhesion.sigma0 = 2e8;
    const FitSummary s = fit(c, guess, retract_options({FitParameter::E, FitParameter::w, FitParameter::sigma0}));
    INFO(s.brief_report());
    CHECK(s.converged);
    CHECK(s.model == "maugis_dugdale on half_space");
    CHECK(rel_err(s[FitParameter::E].value, 1e9) < 1e-5);
    CHECK(rel_err(s[FitParameter::w].value, 0.05) < 1e-5);
    CHECK(rel_err(s[FitParameter::sigma0].value, 1e8) < 1e-5);
  }
}

TEST_CASE("Dugdale laws a fit cannot solve are refused with one clear message", "[fit][adhesion][dugdale]") {
  const CurveData c = retract_from(law_of(scene_from(R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "half_space", "E": 1e9, "nu": 0.3}, "w": 0.05, "adhesion": {"model": "dmt"}})")),
                                   5e-9, 0.0, 1);
  auto message = [&](const std::string& json, std::vector<FitParameter> free) {
    return test::input_error([&] { fit(c, scene_from(json), retract_options(std::move(free))); });
  };
  // A thin-layer law gives no gap outside the contact.
  CHECK_THAT(message(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "layer", "E": 1e9,
      "nu": 0.5, "h": 1e-8}, "model": "incompressible", "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})",
                     {FitParameter::E, FitParameter::w}),
             Catch::Contains("maugis_dugdale") && Catch::Contains("'incompressible'") &&
                 Catch::Contains("model 'exact'"));
  CHECK_THAT(message(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "winkler", "K": 1e15},
      "adhesion": {"model": "dmt", "z0": 3e-10}})", {FitParameter::K, FitParameter::w}),
             Catch::Contains("'dmt'") && Catch::Contains("'winkler'"));
  // A free sigma0 is placed between its limits by Maugis' lambda of the tip's radius: a cone has none.
  CHECK_THAT(message(R"({"indenter": {"shape": "cone", "semi_angle_deg": 70}, "medium": {"type": "half_space",
      "E": 1e9, "nu": 0.3}, "adhesion": {"model": "maugis_dugdale", "sigma0": 1e8}})",
                     {FitParameter::E, FitParameter::w, FitParameter::sigma0}),
             Catch::Contains("sigma0") && Catch::Contains("radius of curvature"));
  // The Dugdale DMT has no free sigma0.
  CHECK_THAT(message(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": {"type": "half_space", "E": 1e9,
      "nu": 0.3}, "adhesion": {"model": "dmt", "sigma0": 1e8}})", {FitParameter::E, FitParameter::w, FitParameter::sigma0}),
             Catch::Contains("sigma0") && Catch::Contains("'dmt'"));
}
