// JKR rigs: a 5 mm glass sphere on a 100 um bonded PDMS film (E = 1 MPa, nu = 0.49, w = 0.05
// J/m^2), loaded from its zero-load contact and unloaded under displacement control past the
// load-controlled pull-off (-1.5 mN), every sample in contact; the truth is the library's exact
// layer, with 2 uN of noise. With default (automatic) control the fit sees the displacement
// control in the data; (P, a) data - the load against the contact radius, no displacement - fit
// E and w from a linear start; delta,P,a data weigh each column by its own noise.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "layerjkr/answer.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

using namespace layerjkr;

namespace {

constexpr double kNoise = 2e-6;  // N

Scene rig(double E = 1e6) {
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-3},
      "medium": {"type": "layer", "E": )" + format_double(E) + R"(, "nu": 0.49, "h": 1e-4, "base": "bonded"},
      "model": "exact", "w": 0.05})",
                     "rig");
}

// The truth on a fine grid of radii, 20 to 400 um.
struct Truth {
  std::vector<double> a, P, delta;
};
Truth truth() {
  std::vector<double> radii;
  for (int k = 0; k <= 1500; ++k) radii.push_back(20e-6 + 380e-6 * k / 1500.0);
  const CurveAnswer c = solve_curve(rig(), radii);
  Truth t;
  for (const AdhesiveState& s : c.states) {
    t.a.push_back(s.a);
    t.P.push_back(s.P);
    t.delta.push_back(s.delta);
  }
  return t;
}

// Samples even in delta from radius a_from to a_to along the stable branch (delta grows with a
// there), force interpolated; `with_radius` also records a.
CurveData rig_curve(bool with_radius, double radius_noise, unsigned seed) {
  const Truth t = truth();
  std::size_t zero = 0;  // the zero-load radius on the stable branch
  for (std::size_t i = 1; i < t.P.size(); ++i)
    if (t.P[i - 1] < 0.0 && t.P[i] >= 0.0) zero = i;
  std::size_t lowest = 0;  // the lowest radius unloading reaches: past the pull-off, above the grips point
  while (t.a[lowest] < 32e-6) ++lowest;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  c.source = "rig";
  const auto sample = [&](std::size_t from, std::size_t to, int n, int segment) {
    const double d0 = t.delta[from], d1 = t.delta[to];
    for (int k = 0; k < n; ++k) {
      const double d = d0 + (d1 - d0) * k / (n - 1.0);
      std::size_t j = std::min(from, to);
      while (j + 1 < std::max(from, to) && t.delta[j + 1] < d) ++j;
      const double f = (d - t.delta[j]) / (t.delta[j + 1] - t.delta[j]);
      c.delta.push_back(d + 5e-6);
      c.P.push_back(t.P[j] + f * (t.P[j + 1] - t.P[j]) + kNoise * g(rng));
      if (with_radius) c.a.push_back(t.a[j] + f * (t.a[j + 1] - t.a[j]) + radius_noise * g(rng));
      c.segment.push_back(segment);
    }
  };
  sample(zero, t.a.size() - 1, 300, 0);    // loading from zero load to 400 um
  sample(t.a.size() - 1, lowest, 300, 1);  // unloading past the pull-off, in contact
  return c;
}

// The rigs of issue 40, where fits depended on the noise draw: loading from the zero-load contact
// radius (the jump-in) to a_max, unloading to a_end, `n` samples each even in delta along the
// stable branch, 2 uN of force noise and 50 nm of displacement noise.
CurveData noisy_rig(const Scene& truth, double a_max, double a_end, unsigned seed, double delta_noise = 50e-9) {
  std::vector<double> radii;
  for (int k = 0; k <= 3000; ++k) radii.push_back(a_max * (0.01 + 0.99 * k / 3000.0));
  const CurveAnswer c = solve_curve(truth, radii);
  std::vector<double> a, P, delta;
  for (const AdhesiveState& st : c.states) {
    a.push_back(st.a);
    P.push_back(st.P);
    delta.push_back(st.delta);
  }
  const std::size_t grips = static_cast<std::size_t>(std::min_element(delta.begin(), delta.end()) - delta.begin());
  std::size_t zero = grips, end = grips;
  while (zero + 1 < P.size() && P[zero] < 0.0) ++zero;
  while (end + 1 < a.size() && a[end] < a_end) ++end;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData out;
  out.source = "rig";
  const auto sample = [&](std::size_t from, std::size_t to, int segment) {
    for (int k = 0; k < 200; ++k) {
      const double d = delta[from] + (delta[to] - delta[from]) * k / 199.0;
      std::size_t j = std::min(from, to);
      while (j + 1 < std::max(from, to) && delta[j + 1] < d) ++j;
      const double f = (d - delta[j]) / (delta[j + 1] - delta[j]);
      out.delta.push_back(d + delta_noise * g(rng));
      out.P.push_back(P[j] + f * (P[j + 1] - P[j]) + kNoise * g(rng));
      out.segment.push_back(segment);
    }
  };
  sample(zero, a.size() - 1, 0);
  sample(a.size() - 1, end, 1);
  return out;
}

FitOptions options(std::vector<FitParameter> free, RetractControl control) {
  FitOptions o;
  o.free = std::move(free);
  o.branch = Branch::all;
  o.retract_control = control;
  return o;
}

void check_truth(const FitSummary& s) {
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(std::abs(s[FitParameter::E].value - 1e6) < 3.0 * s[FitParameter::E].standard_error);
  CHECK(std::abs(s[FitParameter::w].value - 0.05) < 3.0 * s[FitParameter::w].standard_error);
  CHECK_FALSE(s.residual_structure);
  CHECK(s.identifiable);
}

}  // namespace

TEST_CASE("a JKR rig unloaded under displacement control: automatic control sees it, E and w within their error bars",
          "[fit][rig]") {
  const CurveData c = rig_curve(false, 0.0, 3);
  REQUIRE(*std::min_element(c.P.begin(), c.P.end()) < -1.4e-3);  // past the load-controlled pull-off
  const auto free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  const FitSummary automatic = fit(c, rig(3e5), options(free, RetractControl::automatic));  // a start 3x soft
  check_truth(automatic);
  const auto says = [](const FitSummary& s, const char* text) {
    return std::any_of(s.notices.begin(), s.notices.end(), [&](const std::string& n) { return n.find(text) != std::string::npos; });
  };
  CHECK(says(automatic, "retract control: fixed grips, chosen from the data"));
  CHECK(says(automatic, "is the contact's own branch"));
  CHECK(automatic.excluded_count == 0);
  CHECK(automatic.rms_residual < 1.2 * kNoise);
  // Load control, as asked: load control cannot hold the contact past the force minimum, so the
  // rise after it is read as a tail and excluded - said - and E and w come from the samples down
  // to the minimum, still right.
  const FitSummary load = fit(c, rig(3e5), options(free, RetractControl::load));
  INFO(load.brief_report());
  CHECK(says(load, "retract control: load (as asked)"));
  CHECK(load.excluded_count > 0);
  CHECK(std::abs(load[FitParameter::E].value - 1e6) < 3.0 * load[FitParameter::E].standard_error);
  CHECK(std::abs(load[FitParameter::w].value - 0.05) < 3.0 * load[FitParameter::w].standard_error);
}

TEST_CASE("(P, a) data: a rig's load against its contact radius, no displacement, fits E and w", "[fit][rig]") {
  CurveData c = rig_curve(true, 0.0, 5);
  c.delta.clear();  // the rig's classic record: load and radius only
  REQUIRE(c.radius_only());
  const FitSummary s = fit(c, rig(3e5), options({FitParameter::E, FitParameter::w}, RetractControl::automatic));
  check_truth(s);
  CHECK(s.points_in_contact == c.size());
  const FitSummary with_P0 = fit(c, rig(3e5), options({FitParameter::E, FitParameter::w, FitParameter::P0},
                                                       RetractControl::automatic));
  check_truth(with_P0);
  CHECK(std::abs(with_P0[FitParameter::P0].value) < 3.0 * with_P0[FitParameter::P0].standard_error);
  CHECK_THROWS_WITH(fit(c, rig(), options({FitParameter::E, FitParameter::delta0}, RetractControl::automatic)),
                    Catch::Contains("(P, a) data have no displacement") && Catch::Contains("delta0"));
}

TEST_CASE("delta,P,a data: each column's residuals weigh by its own noise, estimated or given", "[fit][rig]") {
  const double radius_noise = 1e-6;  // m, about 0.5 % of the radii
  const CurveData c = rig_curve(true, radius_noise, 7);
  FitOptions o = options({FitParameter::E, FitParameter::w, FitParameter::delta0}, RetractControl::fixed_grips);
  const FitSummary estimated = fit(c, rig(3e5), o);
  check_truth(estimated);
  CHECK(estimated.force_noise == Approx(kNoise).epsilon(0.2));
  CHECK(estimated.radius_noise == Approx(radius_noise).epsilon(0.2));
  CHECK_FALSE(estimated.force_noise_given);
  o.force_noise = kNoise;
  o.radius_noise = radius_noise;
  const FitSummary given = fit(c, rig(3e5), o);
  check_truth(given);
  CHECK(given.force_noise == kNoise);
  CHECK(given.radius_noise_given);
  CHECK_THAT(given.brief_report(), Catch::Contains("noise: P 2e-06 N (given), a 1e-06 m (given)"));
}

TEST_CASE("JKR rigs under eight noise draws: every fit right from a start 2x soft, never 'no adhesion'", "[fit][rig]") {
  // Issue 40: the same curves with 8 noise draws gave w = 0 and E 5-12 % high in 2-6 of 8 draws
  // ("the data show no adhesion on this branch" beside a pull-off of -1.5 mN), because which
  // samples counted and the retract's control moved with the fit.
  const Scene half_space = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-3},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.49}, "w": 0.05})");
  const Scene start_half_space = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-3},
      "medium": {"type": "half_space", "E": 5e5, "nu": 0.49}, "w": 0.02})");
  Scene start_film = rig(5e5);
  start_film.w = 0.02;
  struct Rig {
    const Scene* truth;
    const Scene* start;
    double a_max, a_end;  // a/h 0.5-4.5 on the film; unloading past the pull-off on the half-space
  };
  const Scene film = rig();
  // Half-space: pull-off at a = 150 um, fixed grips at 95 um; film: the unloading ends at 60 um,
  // before the load-controlled pull-off.
  for (const Rig& r : {Rig{&half_space, &start_half_space, 4e-4, 1.05e-4}, Rig{&film, &start_film, 4.5e-4, 6e-5}})
    for (unsigned seed = 1; seed <= 8; ++seed) {
      const CurveData c = noisy_rig(*r.truth, r.a_max, r.a_end, seed);
      const FitSummary s = fit(c, *r.start, options({FitParameter::E, FitParameter::w, FitParameter::delta0}, RetractControl::automatic));
      INFO((r.truth == &film ? "film" : "half-space") << ", seed " << seed << "\n" << s.brief_report());
      CHECK(s.converged);
      CHECK(std::abs(s[FitParameter::E].value - 1e6) < 3.0 * s[FitParameter::E].standard_error);
      CHECK(std::abs(s[FitParameter::w].value - 0.05) < 3.0 * s[FitParameter::w].standard_error);
      CHECK(s.brief_report().find("no adhesion") == std::string::npos);
      CHECK(s.pull_off_force < -1e-3);
    }
}

TEST_CASE("a rig's displacement noise larger than its step still counts in the data's noise", "[fit][rig]") {
  // The noise the residuals are judged by is the force's and the displacement's times the curve's
  // slope. The slope came from neighbours two samples apart only where their displacements differed
  // by 4 noise sigmas: with noise 6x the step no pair qualified, the noise was the force's alone
  // (2.2 uN against 0.36 mN of residuals, "166 times the data's noise") and a good fit of such
  // data read as "the model does not describe these data". Now the pair widens until the step
  // exceeds the noise (0.37 mN).
  const Scene half_space = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 5e-3},
      "medium": {"type": "half_space", "E": 1e6, "nu": 0.49}, "w": 0.05})");
  const CurveData quiet = noisy_rig(half_space, 4e-4, 1.05e-4, 3, 0.0);
  const double step = std::abs(quiet.delta[1] - quiet.delta[0]);
  const CurveData c = noisy_rig(half_space, 4e-4, 1.05e-4, 3, 6.0 * step);
  const FitSummary s = fit(c, half_space, options({FitParameter::E, FitParameter::w, FitParameter::delta0},
                                                  RetractControl::automatic));
  INFO(s.brief_report());
  CHECK(s.noise > 20.0 * kNoise);  // the force's 2 uN is not the whole noise
  CHECK(s.rms_residual < 2.0 * s.noise);
  CHECK_FALSE(s.residual_structure);
}
