// The retract read from its samples alone (src/fit/data/retract_reading.cpp): the baseline from the
// free parts, the measured pull-off, the release and the tail - on hand-made retracts whose
// answer is known - and the fit's honest convergence (judge_plausibility). The pull-off is one
// number whatever the fit does.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "fit/run/fit_steps.hpp"
#include "fit/data/retract_reading.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/simulate.hpp"
#include "support/catch_after_glog.hpp"

using namespace layerjkr;
using detail::FitData;
using detail::Release;

namespace {

constexpr double kNoise = 1e-11;  // N

// An approach of `free_n` samples at rest then a rise, and a retract of `retract` forces (in
// acquisition order) shifted by `baseline`, with Gaussian noise; delta falls on retract.
FitData curve(const std::vector<double>& retract, double baseline, unsigned seed = 1, int free_n = 30) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, kNoise);
  FitData d;
  const auto add = [&](double delta, double P, bool r) {
    d.delta.push_back(delta);
    d.P.push_back(P + baseline + g(rng));
    d.retract.push_back(r);
    d.sqrt_weight.push_back(1.0);
  };
  for (int i = 0; i < free_n; ++i) add(1e-9 * i, 0.0, false);
  for (int i = 0; i < 30; ++i) add(1e-9 * (free_n + i), 2e-11 * i * i, false);
  for (std::size_t k = 0; k < retract.size(); ++k) add(1e-9 * (free_n + 30) - 1e-9 * static_cast<double>(k), retract[k], true);
  return d;
}

// A retract from 1.8e-8 N falling linearly to -1e-8 N (the pull-off) in 40 samples, then `after`.
std::vector<double> falling(const std::vector<double>& after) {
  std::vector<double> r;
  for (int k = 0; k < 40; ++k) r.push_back(1.8e-8 - 2.8e-8 * k / 39.0);
  r.insert(r.end(), after.begin(), after.end());
  return r;
}

std::vector<double> zeros(int n) { return std::vector<double>(static_cast<std::size_t>(n), 0.0); }

detail::RetractReading read(const FitData& d, bool hold_gradual_rise = false) {
  FitOptions o;
  o.free = {FitParameter::E};
  return detail::read_retract(d, o, 5e-8, hold_gradual_rise);
}

std::size_t retract_begin(const FitData& d) {
  return static_cast<std::size_t>(std::find(d.retract.begin(), d.retract.end(), true) - d.retract.begin());
}

}  // namespace

TEST_CASE("the pull-off is measured against the retract's free part, else the approach's, else zero", "[fit][retract_reading]") {
  // A snap at the minimum back to a baseline of 3e-10 N: the retract's last tenth is at rest.
  const FitData snap = curve(falling(zeros(30)), 3e-10);
  const detail::PullOffMeasure m = detail::measure_pull_off(snap, 5e-8);
  CHECK(m.has_baseline);
  CHECK_THAT(m.baseline_source, Catch::Contains("last 7 samples of the retract"));
  CHECK(m.baseline == Approx(3e-10).margin(3 * kNoise));
  CHECK(m.pull_off == Approx(-1e-8).margin(4 * kNoise));
  CHECK(m.noise == Approx(kNoise).epsilon(0.5));
  CHECK(m.adhesive);
  // The retract ends rising (still in contact): the approach's first tenth is the baseline.
  std::vector<double> rising;
  for (int k = 1; k <= 20; ++k) rising.push_back(-1e-8 + 2e-10 * k);
  const detail::PullOffMeasure a = detail::measure_pull_off(curve(falling(rising), 3e-10), 5e-8);
  CHECK_THAT(a.baseline_source, Catch::Contains("first"));
  CHECK(a.baseline == Approx(3e-10).margin(3 * kNoise));
  // Neither at rest (no approach, a retract rising to its end): the force's zero.
  FitData none = curve(falling(rising), 3e-10, 1, 0);
  none.delta.erase(none.delta.begin(), none.delta.begin() + 30);
  none.P.erase(none.P.begin(), none.P.begin() + 30);
  none.retract.erase(none.retract.begin(), none.retract.begin() + 30);
  none.sqrt_weight.erase(none.sqrt_weight.begin(), none.sqrt_weight.begin() + 30);
  const detail::PullOffMeasure z = detail::measure_pull_off(none, 5e-8);
  CHECK_FALSE(z.has_baseline);
  CHECK(z.baseline == 0.0);
  CHECK_THAT(z.baseline_source, Catch::Contains("the force's zero"));
}

TEST_CASE("the release is read from the samples: a snap, a held branch, a contact held to the end, a tail", "[fit][retract_reading]") {
  SECTION("a snap at the minimum: every later sample free, none excluded") {
    const FitData d = curve(falling(zeros(30)), 0.0);
    const detail::RetractReading r = read(d);
    CHECK(r.release == Release::at_minimum);
    CHECK(r.held_past_minimum == 0);
    CHECK(r.tail_count == 0);
    const std::size_t b = retract_begin(d);
    for (std::size_t k = 0; k < 40; ++k) CHECK(r.contact[b + k] == 1);
    for (std::size_t k = 40; k < 70; ++k) CHECK(r.contact[b + k] == 0);
  }
  SECTION("held past the minimum then released by a jump, with a tail after it") {
    std::vector<double> after;
    for (int k = 1; k <= 8; ++k) after.push_back(-1e-8 + 5e-10 * k);           // the branch, rising
    for (int k = 1; k <= 6; ++k) after.push_back(-1e-9 * std::exp(-k / 2.0));  // after the jump: a tail
    const std::vector<double> z = zeros(30);
    after.insert(after.end(), z.begin(), z.end());
    const FitData d = curve(falling(after), 0.0);
    const detail::RetractReading r = read(d);
    CHECK(r.release == Release::held_then_jump);
    CHECK(r.held_past_minimum == 8);
    CHECK(r.jump == Approx(6e-9 - 1e-9 * std::exp(-0.5)).margin(4 * kNoise));
    CHECK(r.tail_count >= 3);
    CHECK(r.tail_count <= 6);
    const std::size_t b = retract_begin(d);
    for (std::size_t k = 0; k < 48; ++k) CHECK(r.contact[b + k] == 1);
    for (std::size_t k = 48; k < d.P.size() - b; ++k) CHECK(r.contact[b + k] == 0);
  }
  SECTION("the force rises past its minimum and ends far below the baseline: every sample in contact") {
    std::vector<double> after;
    for (int k = 1; k <= 20; ++k) after.push_back(-1e-8 + 2e-10 * k);  // ends at -6e-9 N
    const detail::RetractReading r = read(curve(falling(after), 0.0));
    CHECK(r.release == Release::held_to_end);
    CHECK(r.held_past_minimum == 20);
    CHECK(r.tail_count == 0);
  }
  SECTION("a gradual return to the baseline is a tail; read the other way, the branch held") {
    std::vector<double> after;
    for (int k = 1; k <= 15; ++k) after.push_back(-1e-8 * std::exp(-k / 4.0));  // steps shrink by 0.78
    const std::vector<double> z = zeros(30);
    after.insert(after.end(), z.begin(), z.end());
    const FitData d = curve(falling(after), 0.0);
    const detail::RetractReading tail = read(d);
    CHECK(tail.release == Release::gradual);
    CHECK(tail.tail_count >= 10);
    CHECK_THAT(tail.rule, Catch::Contains("without a jump"));
    const detail::RetractReading held = read(d, true);
    CHECK(held.release == Release::held_gradual);
    CHECK(held.tail_count == 0);
    CHECK(held.held_past_minimum >= 10);
  }
  SECTION("a held gradual return still below the baseline inside its noise band: excluded until it settles") {
    // The return enters the 3-sigma band at k ~ 23 but lies below the baseline by more than the
    // mean of 5 samples resolves (1e-11 / sqrt(5)) until k ~ 31: neither clearly in contact nor at rest.
    std::vector<double> after;
    for (int k = 1; k <= 45; ++k) after.push_back(-1e-8 * std::exp(-k / 4.0));
    const std::vector<double> z = zeros(30);
    after.insert(after.end(), z.begin(), z.end());
    const FitData d = curve(falling(after), 0.0);
    const detail::RetractReading held = read(d, true);
    REQUIRE(held.release == Release::held_gradual);
    CHECK(held.tail_count >= 3);
    CHECK(held.tail_count <= 15);
    CHECK_THAT(held.rule, Catch::Contains("until the return settles"));
    const std::size_t b = retract_begin(d), first_tail = b + 40 + held.held_past_minimum;
    for (std::size_t i = b; i < first_tail; ++i) CHECK(held.contact[i] == 1);
    for (std::size_t i = first_tail; i < first_tail + held.tail_count; ++i) CHECK(held.tail[i]);
    for (std::size_t i = first_tail + held.tail_count; i < d.P.size(); ++i) {
      CHECK(held.contact[i] == 0);
      CHECK_FALSE(held.tail[i]);
    }
  }
  SECTION("a held gradual return that settles later than the held branch is long: nothing more excluded") {
    // Into the band within ~9 samples, then 40 samples creeping from -2.5 sigma towards the
    // baseline: longer in the band than the branch was held, so not a branch ending near zero force.
    std::vector<double> after;
    for (int k = 1; k <= 9; ++k) after.push_back(-1e-8 * std::exp(-k / 1.5));
    for (int k = 1; k <= 40; ++k) after.push_back(-2.5e-11 * std::exp(-k / 30.0));
    const std::vector<double> z = zeros(30);
    after.insert(after.end(), z.begin(), z.end());
    const FitData d = curve(falling(after), 0.0);
    const detail::RetractReading held = read(d, true);
    REQUIRE(held.release == Release::held_gradual);
    CHECK(held.held_past_minimum <= 10);
    CHECK(held.tail_count == 0);
  }
  SECTION("the data end at the minimum: every retract sample in contact") {
    const detail::RetractReading r = read(curve(falling({}), 0.0));
    CHECK(r.release == Release::at_end);
    CHECK(r.tail_count == 0);
  }
  SECTION("no force below the baseline beyond noise: the model places every sample") {
    std::vector<double> r;
    for (int k = 0; k < 40; ++k) r.push_back(1.8e-8 * (1.0 - k / 39.0));
    const std::vector<double> z = zeros(30);
    r.insert(r.end(), z.begin(), z.end());
    const detail::RetractReading none = read(curve(r, 0.0));
    CHECK(none.release == Release::none);
    CHECK(none.contact.empty());
  }
}

TEST_CASE("one measured pull-off: the same number whatever is free and wherever the fit starts", "[fit][retract_reading]") {
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "half_space", "E": 2e4, "nu": 0.5}, "w": 1e-4})");
  SimulationOptions so;
  so.max_indentation = 1e-6;
  so.noise = 2e-11;
  so.P0 = 5e-11;
  const CurveData c = simulate_curve(truth, so);
  double first = std::numeric_limits<double>::quiet_NaN();
  for (double start : {0.1, 1.0, 10.0})
    for (const auto& free : {std::vector<FitParameter>{FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0},
                             std::vector<FitParameter>{FitParameter::E, FitParameter::delta0}}) {
      Scene s = truth;
      s.medium.E *= start;
      FitOptions o;
      o.free = free;
      o.branch = Branch::all;
      const FitSummary f = fit(c, s, o);
      INFO(f.brief_report());
      if (std::isnan(first)) first = f.pull_off_force;
      CHECK(f.pull_off_force == first);  // bit for bit: no fitted value enters it
      CHECK(f.pull_off_baseline == Approx(5e-11).margin(2e-11));
      CHECK(f.pull_off_force == Approx(-1.5 * M_PI * 1e-4 * 1e-5).epsilon(0.02));
    }
}

TEST_CASE("absurd parameters or residuals far above the noise are a failed fit, never converged", "[fit][plausibility]") {
  FitSummary s;
  s.converged = true;
  s.identifiable = true;
  s.termination = "Function tolerance reached";
  ParameterEstimate E;
  E.parameter = FitParameter::E;
  E.value = 1.86e42;
  E.standard_error = 1.0;
  s.parameters.push_back(E);
  detail::judge_plausibility(&s);
  CHECK_FALSE(s.converged);
  CHECK_FALSE(s.identifiable);
  CHECK_THAT(s.failure, Catch::Contains("E = 1.86e+42 Pa lies outside every physical modulus"));
  CHECK_THAT(s.brief_report(), Catch::StartsWith("layerjkr fit: NOT converged") && Catch::Contains("failed: E = 1.86e+42"));
  BatchItem item;
  item.ok = false;  // fit_batch's verdict on such a summary, with its reason
  item.summary = s;
  CHECK(batch_quality(item) == "failed");

  FitSummary w = FitSummary();
  w.converged = true;
  ParameterEstimate work;
  work.parameter = FitParameter::w;
  work.value = 1.7e33;
  w.parameters.push_back(work);
  detail::judge_plausibility(&w);
  CHECK_THAT(w.failure, Catch::Contains("exceeds every physical work of adhesion"));

  // Residuals 1e3 times the noise: failed with structure (few runs), kept without it (residuals
  // that alternate as noise does are noise the estimate missed).
  for (const double runs_z : {-30.0, 0.3}) {
    FitSummary r;
    r.converged = true;
    r.P = {0.0, 1.0};
    r.noise = 1e-3;
    r.rms_residual = 1.0;
    r.runs_z = runs_z;
    detail::judge_plausibility(&r);
    CHECK(r.converged == (runs_z > 0.0));
    if (runs_z < 0.0) CHECK_THAT(r.failure, Catch::Contains("1000 times the data's noise"));
  }
  // A high-SNR curve a model follows to 2 % of its span (SOFA's Asylum maps under Hertz: 100-470
  // noise sigmas, 2-7 % of the span) is described, with structure: not a failed fit.
  FitSummary close;
  close.converged = true;
  close.P = {0.0, 0.25, 0.5, 0.75, 1.0};  // spread about the mean 0.354
  close.noise = 1e-4;
  close.rms_residual = 0.02;
  close.runs_z = -30.0;
  detail::judge_plausibility(&close);
  CHECK(close.converged);
  close.rms_residual = 0.2;  // 57 % of the spread: no better than a constant's residual
  detail::judge_plausibility(&close);
  CHECK_FALSE(close.converged);
  CHECK_THAT(close.failure, Catch::Contains("% of the forces' own spread about their mean"));
  FitSummary fine;
  fine.converged = true;
  fine.P = {0.0, 1.0};
  fine.noise = 1e-3;
  fine.rms_residual = 1.1e-3;
  fine.runs_z = -30.0;
  detail::judge_plausibility(&fine);
  CHECK(fine.converged);
  CHECK(fine.failure.empty());
}

TEST_CASE("a free part that drifts a little is still at rest where the other agrees with it", "[fit][retract_reading]") {
  // Asylum's maps (SOFA's public test data): the retract's last tenth trends by 1.7 nN, 4 third-
  // difference noise sigmas but 0.07 % of the 2.3 uN span, and the approach's first tenth sits
  // at the same level. Read strictly, neither was at rest and the pull-off was measured from the
  // force's zero: 3x the vendor's adhesion. Now 1 972 of the 1 976 curves of the three maps are
  // within 5 % of Asylum's MapAdhesion (median 0.02-0.16 %).
  std::vector<double> after;
  for (int k = 0; k < 30; ++k) after.push_back(3e-10 * k / 29.0);  // 30 noise sigmas of drift, 0.6 % of the span
  FitData d = curve(falling(after), 0.0);
  for (std::size_t i = 0; i < 30; ++i) d.P[i] += 1.5e-10;  // the approach's start at the drifting level's middle
  const detail::PullOffMeasure m = detail::measure_pull_off(d, 5e-8);
  CHECK(m.has_baseline);
  CHECK_THAT(m.baseline_source, Catch::Contains("retract"));
  const double tail_median = 3e-10 * 26.0 / 29.0;  // the median of the retract's last 7 samples
  CHECK(m.baseline == Approx(tail_median).margin(3 * kNoise));
  CHECK(m.pull_off == Approx(-1e-8 - tail_median).margin(6 * kNoise));
  // The same end far from the approach's level (a rig near its grips limit): not at rest.
  std::vector<double> held;
  for (int k = 0; k < 30; ++k) held.push_back(-6e-9 + 3e-10 * k / 29.0);
  const detail::PullOffMeasure rig = detail::measure_pull_off(curve(falling(held), 0.0), 5e-8);
  CHECK_THAT(rig.baseline_source, Catch::Contains("first"));  // the approach's own, at 0
  CHECK(rig.baseline == Approx(0.0).margin(3 * kNoise));
}
