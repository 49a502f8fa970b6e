// The retract as a cantilever makes it: the tip follows the adhesive branch past the
// load-controlled pull-off until dP/d delta = -k, then jumps free. Synthetic retracts made
// with a known k - with and without a non-JKR tail after the jump - must give back E, w,
// delta0 and P0 within their error bars, with the tail excluded and counted.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include <boost/math/tools/roots.hpp>

#include "layerjkr/contact.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {

constexpr double kE = 1e5, kNu = 0.5, kW = 0.01, kR = 2e-6, kDelta0 = 1e-6, kP0 = 2e-9, kK = 0.05;

// The radius where a cantilever of stiffness k lets go: dP/da + k d delta/da = 0 between the
// fixed-grips point and the pull-off (central differences of the closed-form Hertz JKR).
double jump_radius(const JkrSolution& jkr, double k) {
  const double a_po = jkr.pull_off()->a, a_fg = jkr.fixed_grips_critical()->a;
  auto g = [&](double a) {
    const double h = 1e-6 * a;
    const AdhesiveState lo = jkr.at(a - h), hi = jkr.at(a + h);
    return (hi.P - lo.P) + k * (hi.delta - lo.delta);
  };
  std::uintmax_t iters = 200;
  const auto r = boost::math::tools::toms748_solve(g, a_fg * 1.0001, a_po, boost::math::tools::eps_tolerance<double>(40), iters);
  return 0.5 * (r.first + r.second);
}

// Retract samples: on the branch from a_max down to the jump, then detached over as long
// again; a tail decays from the jump force to the baseline over `tail_length` (0: none).
CurveData synthetic_retract(double tail_length, double noise, unsigned seed) {
  const JkrSolution jkr(make_half_space(make_paraboloid(kR), kE, kNu), kW);
  const double a_jump = jump_radius(jkr, kK), a_max = 4.0 * jkr.pull_off()->a;
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  CurveData c;
  const int n_contact = 300, n_free = 300;
  for (int i = 0; i < n_contact; ++i) {
    const AdhesiveState s = jkr.at(a_max - (a_max - a_jump) * i / (n_contact - 1));
    c.delta.push_back(s.delta + kDelta0);
    c.P.push_back(s.P + kP0 + gauss(rng));
  }
  const AdhesiveState jump = jkr.at(a_jump);
  const double span = jkr.at(a_max).delta - jump.delta;
  for (int i = 1; i <= n_free; ++i) {
    const double back = span * i / n_free;
    const double tail = tail_length > 0.0 ? jump.P * std::exp(-back / tail_length) : 0.0;
    c.delta.push_back(jump.delta - back + kDelta0);
    c.P.push_back(kP0 + tail + gauss(rng));
  }
  c.segment.assign(c.delta.size(), 1);
  c.source = "synthetic retract";
  return c;
}

FitSummary fit_retract(const CurveData& c, double k, double exclusion_sigmas = 3.0,
                       void (*adjust)(FitOptions&) = nullptr) {
  const Scene scene = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-6},
      "medium": {"type": "half_space", "E": 3e4, "nu": 0.5}})");
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0};
  o.branch = Branch::retract;
  o.retract_control = RetractControl::cantilever;
  o.cantilever_stiffness = k;
  o.exclusion_sigmas = exclusion_sigmas;
  if (adjust) adjust(o);
  return fit(c, scene, o);
}

void check_recovered(const FitSummary& s, double sigmas) {
  INFO(s.brief_report());
  REQUIRE(s.converged);
  CHECK(std::abs(s[FitParameter::E].value - kE) < sigmas * s[FitParameter::E].standard_error);
  CHECK(std::abs(s[FitParameter::w].value - kW) < sigmas * s[FitParameter::w].standard_error);
  CHECK(std::abs(s[FitParameter::delta0].value - kDelta0) < sigmas * s[FitParameter::delta0].standard_error);
  CHECK(std::abs(s[FitParameter::P0].value - kP0) < sigmas * s[FitParameter::P0].standard_error);
}

}  // namespace

TEST_CASE("cantilever retract, noiseless: exact recovery, nothing excluded", "[fit][cantilever]") {
  const FitSummary s = fit_retract(synthetic_retract(0.0, 0.0, 1), kK);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, kE) < 1e-7);
  CHECK(rel_err(s[FitParameter::w].value, kW) < 1e-7);
  CHECK(s.excluded_count == 0);
  // The measured pull-off is the branch's minimum: -3/2 pi w R for a paraboloid on a half-space.
  CHECK(rel_err(s.pull_off_force, -1.5 * M_PI * kW * kR) < 1e-3);
}

TEST_CASE("cantilever retract with noise: parameters and baseline within their error bars", "[fit][cantilever]") {
  const double noise = 2e-3 * 1.5 * M_PI * kW * kR;
  for (unsigned seed : {1u, 2u, 3u}) {
    const FitSummary s = fit_retract(synthetic_retract(0.0, noise, seed), kK);
    check_recovered(s, 4.0);
    CHECK(s.excluded_count <= 3);  // a 3-sigma rule excludes ~0.3 % of pure noise at most
  }
}

TEST_CASE("a non-JKR tail after the jump is excluded, counted, and does not bias the baseline", "[fit][cantilever]") {
  const double noise = 2e-3 * 1.5 * M_PI * kW * kR;
  const CurveData c = synthetic_retract(0.1e-6, noise, 7);  // decays over 100 nm
  const FitSummary s = fit_retract(c, kK);
  check_recovered(s, 4.0);
  CHECK(s.excluded_count > 10);
  REQUIRE(s.excluded.size() == c.size());
  CHECK_FALSE(s.excluded[0]);        // in contact
  CHECK_FALSE(s.excluded.back());    // back at the baseline
  CHECK(s.brief_report().find("excluded") != std::string::npos);
  // Without the rule the tail drags the baseline below its true value.
  const FitSummary kept = fit_retract(c, kK, 0.0);
  CHECK(kept.excluded_count == 0);
  CHECK(kept[FitParameter::P0].value < kP0 - 4.0 * s[FitParameter::P0].standard_error);
}

TEST_CASE("the model lets go where the cantilever did - bad options name themselves", "[fit][cantilever]") {
  const FitSummary s = fit_retract(synthetic_retract(0.0, 0.0, 1), kK);
  CHECK(s.points_in_contact == 300);  // every sample up to the jump, none after it
  FitOptions bad;
  bad.free = {FitParameter::E};
  bad.cantilever_stiffness = -1.0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("cantilever_stiffness") && Catch::Contains("-1"));
  bad.cantilever_stiffness = 0.0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("cantilever_stiffness") && Catch::Contains("> 0"));
  bad.cantilever_stiffness.reset();
  bad.exclusion_sigmas = -2.0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("exclusion_sigmas"));
}

// Two fits gave the same answer, bit for bit.
bool same_fit(const FitSummary& a, const FitSummary& b) {
  for (std::size_t j = 0; j < a.parameters.size(); ++j)
    if (a.parameters[j].value != b.parameters[j].value) return false;
  return a.excluded_count == b.excluded_count && a.points_in_contact == b.points_in_contact;
}

TEST_CASE("the retract control: typed, with the curve's own spring constant by default", "[fit][cantilever]") {
  // A non-JKR tail after the jump: the controls let go at different samples, so they differ.
  CurveData c = synthetic_retract(0.1e-6, 1e-3 * 1.5 * M_PI * kW * kR, 5);
  const FitSummary given = fit_retract(c, kK);
  // No stiffness given: the curve's own (an instrument file's) is used; the same fit.
  c.spring_constant = kK;
  const FitSummary own = fit_retract(c, kK, 3.0, [](FitOptions& o) { o.cantilever_stiffness.reset(); });
  CHECK(same_fit(own, given));
  const FitSummary automatic = fit_retract(c, kK, 3.0, [](FitOptions& o) {
    o.retract_control = RetractControl::automatic;
    o.cantilever_stiffness.reset();
  });
  CHECK(same_fit(automatic, given));
  // Without any stiffness, the retract's gradual return after the force minimum is read both as a
  // tail (load control) and as the branch held under fixed grips: auto keeps the one that follows
  // every sample better and says so; cantilever refuses, naming the curve.
  c.spring_constant = 0.0;
  c.source = "retract.csv";
  const FitSummary load = fit_retract(c, kK, 3.0, [](FitOptions& o) { o.retract_control = RetractControl::load; });
  const FitSummary grips = fit_retract(c, kK, 3.0, [](FitOptions& o) { o.retract_control = RetractControl::fixed_grips; });
  const FitSummary fallback = fit_retract(c, kK, 3.0, [](FitOptions& o) {
    o.retract_control = RetractControl::automatic;
    o.cantilever_stiffness.reset();
  });
  const auto misfit = [](const FitSummary& s) {
    double m = 0.0;
    for (std::size_t i = 0; i < s.P.size(); ++i) m += (s.P[i] - s.P_fit[i]) * (s.P[i] - s.P_fit[i]);
    return m;
  };
  CHECK(same_fit(fallback, misfit(grips) < misfit(load) ? grips : load));
  CHECK(std::any_of(fallback.notices.begin(), fallback.notices.end(),
                    [](const std::string& n) { return n.find("retract control: ") != std::string::npos; }));
  // On this curve the tail starts where the lever lets go, and every sample past the force minimum
  // is excluded under either reading, so the controls agree. A retract that jumps where the lever
  // lets go, past the pull-off, is fitted differently under load control (its branch ends earlier).
  const CurveData jumps = synthetic_retract(0.0, 1e-3 * 1.5 * M_PI * kW * kR, 5);
  const FitSummary jumps_load =
      fit_retract(jumps, kK, 3.0, [](FitOptions& o) { o.retract_control = RetractControl::load; });
  const FitSummary jumps_lever = fit_retract(jumps, kK);
  INFO(jumps_lever.brief_report() << jumps_load.brief_report());
  CHECK_FALSE(same_fit(jumps_load, jumps_lever));
  CHECK_THROWS_WITH(fit_retract(c, kK, 3.0, [](FitOptions& o) { o.cantilever_stiffness.reset(); }),
                    Catch::Contains("retract.csv") && Catch::Contains("'cantilever' needs"));
}

TEST_CASE("a tilted baseline is measured off contact and removed", "[fit][cantilever]") {
  const double noise = 2e-3 * 1.5 * M_PI * kW * kR, slope = 2e-4;  // N/m: 0.4 nN over 2 um
  CurveData c = synthetic_retract(0.1e-6, noise, 11);
  for (std::size_t i = 0; i < c.size(); ++i) c.P[i] += slope * (c.delta[i] - kDelta0);
  const FitSummary s = fit_retract(c, kK, 3.0, [](FitOptions& o) { o.baseline = Baseline::tilt; });
  INFO(s.brief_report());
  CHECK(std::abs(s.baseline_slope - slope) < 4.0 * s.baseline_slope_stderr);
  CHECK(std::abs(s[FitParameter::E].value - kE) < 4.0 * s[FitParameter::E].standard_error);
  CHECK(std::abs(s[FitParameter::w].value - kW) < 4.0 * s[FitParameter::w].standard_error);
  CHECK(s.excluded_count > 10);
  CHECK(s.brief_report().find("baseline tilt") != std::string::npos);
}

TEST_CASE("retract windows: down to the pull-off, and the top fraction of the force range", "[fit][cantilever]") {
  // A window has no detached samples, so the baseline must be known: it is removed first
  // (as the linearised-JKR analysis does) and P0 stays fixed at 0.
  CurveData c = synthetic_retract(0.0, 0.0, 1);
  for (double& p : c.P) p -= kP0;
  const FitSummary pull = fit_retract(c, kK, 3.0, [](FitOptions& o) {
    o.retract_window = RetractWindow::to_pull_off;
    o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  });
  INFO(pull.brief_report());
  const auto deepest = std::min_element(c.P.begin(), c.P.end()) - c.P.begin();
  CHECK(pull.points == static_cast<std::size_t>(deepest) + 1);
  CHECK(rel_err(pull[FitParameter::E].value, kE) < 1e-6);
  CHECK(rel_err(pull[FitParameter::w].value, kW) < 1e-6);
  const FitSummary top = fit_retract(c, kK, 3.0, [](FitOptions& o) {
    o.retract_window = RetractWindow::force_fraction;
    o.window_fraction = 0.5;
    o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  });
  INFO(top.brief_report());
  CHECK(top.points < pull.points);
  for (double p : top.P) CHECK(p >= c.P[0] - 0.5 * (c.P[0] - c.P[static_cast<std::size_t>(deepest)]) - 1e-18);
  CHECK(rel_err(top[FitParameter::E].value, kE) < 1e-4);
  FitOptions bad;
  bad.free = {FitParameter::E};
  bad.window_fraction = 0.0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("window_fraction = 0"));
}
