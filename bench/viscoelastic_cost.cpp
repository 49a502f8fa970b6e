// What time costs (issue #34): the hereditary response per sample - O(N M) by exponential states
// (Prony exactly, the power law as a sum of ~60 exponentials) - against the direct O(N^2) sum
// over the pieces for the power law, in the same run; fits in time against an elastic fit of the
// same curve; a kinetic retract and a summary's rate sweep.
//
//   build/bin/viscoelastic_cost --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

double hertz(double d) { return d > 0.0 ? 4.0 / 3.0 * 1333.3 * std::sqrt(5e-6) * std::pow(d, 1.5) : 0.0; }

struct History {
  std::vector<double> t, delta;
};
// A triangle: 1 um at 2 um/s and back, N samples.
History triangle(int n) {
  History h;
  for (int i = 0; i < n; ++i) {
    const double t = 1.0 * i / (n - 1);
    h.t.push_back(t);
    h.delta.push_back(t <= 0.5 ? 2e-6 * t : 1e-6 - 2e-6 * (t - 0.5));
  }
  return h;
}

void BM_Hereditary(benchmark::State& state, const RelaxationLaw& law) {
  const History h = triangle(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(hereditary_response(h.t, h.delta, hertz, law));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK_CAPTURE(BM_Hereditary, sls, RelaxationLaw::standard_linear_solid(0.4, 0.1))->Arg(1000)->Arg(4000)->Arg(16000);
BENCHMARK_CAPTURE(BM_Hereditary, power_law, RelaxationLaw::power_law(0.2, 1.0))->Arg(1000)->Arg(4000)->Arg(16000);

// The peer: the power law's loading by the exact integral of every piece at every sample, O(N^2)
// (what lee_radok_loading did before the sum of exponentials).
void BM_PowerLawDirectSum(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<double> t(n), P(n);
  for (int i = 0; i < n; ++i) t[i] = 0.5 * (i + 1) / n, P[i] = hertz(2e-6 * t[i]);
  const double beta = 0.2, e = 1.0 - beta;
  for (auto _ : state) {
    std::vector<double> out(n);
    for (int m = 0; m < n; ++m) {
      double sum = 0.0, tp = 0.0, Pp = 0.0;
      for (int k = 0; k <= m; ++k) {
        const double slope = (P[k] - Pp) / (t[k] - tp);
        sum += slope * (std::pow(t[m] - tp, e) - std::pow(t[m] - t[k], e)) / e;
        tp = t[k];
        Pp = P[k];
      }
      out[m] = sum;
    }
    benchmark::DoNotOptimize(out);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_PowerLawDirectSum)->Arg(1000)->Arg(4000)->Arg(16000);

const char* kCell = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "layer", "E": 2000, "nu": 0.49,
    "h": 3e-6, "base": "bonded", "viscoelastic": )";

CurveData cell_curve(const std::string& law, double speed, std::uint64_t seed) {
  SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = speed;
  o.points_per_branch = 350;
  o.noise = 5e-11;
  o.seed = seed;
  o.delta0 = 1e-6;
  return simulate_curve(parse_scene(kCell + law + R"(}, "model": "exact"})"), o);
}

// One 700-sample curve of a relaxing bonded layer (nu = 0.49), approach and retract, from a scene
// 2.5x off: the law fitted in time, and the elastic fit of the same curve (the floor).
void BM_FitInTime(benchmark::State& state) {
  const bool power = state.range(0) == 1;
  const std::string truth = power ? R"({"law": "power_law", "beta": 0.15, "t0": 1})" : R"({"law": "sls", "E_inf": 800, "tau": 0.2})";
  const std::string guess = power ? R"({"law": "power_law", "beta": 0.4, "t0": 1})" : R"({"law": "sls", "E_inf": 320, "tau": 0.5})";
  const CurveData c = cell_curve(truth, 2e-6, 1);
  const Scene s = parse_scene(kCell + guess + R"(}, "model": "exact"})");
  FitOptions f;
  f.free = power ? std::vector<FitParameter>{FitParameter::E, FitParameter::beta, FitParameter::delta0}
                 : std::vector<FitParameter>{FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0};
  f.branch = Branch::all;
  for (auto _ : state) benchmark::DoNotOptimize(fit(c, s, f));
}
BENCHMARK(BM_FitInTime)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_ElasticFitFloor(benchmark::State& state) {
  const CurveData c = cell_curve(R"({"law": "sls", "E_inf": 800, "tau": 0.2})", 2e-6, 1);
  Scene s = parse_scene(kCell + std::string(R"({"law": "sls", "E_inf": 320, "tau": 0.5})") + R"(}, "model": "exact"})");
  s.medium.relaxation = RelaxationLaw{};
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::delta0};
  f.branch = Branch::approach;
  for (auto _ : state) benchmark::DoNotOptimize(fit(c, s, f));
}
BENCHMARK(BM_ElasticFitFloor)->Unit(benchmark::kMillisecond);

void BM_FitJointThreeSpeeds(benchmark::State& state) {
  std::vector<CurveData> curves;
  for (double v : {0.5e-6, 2e-6, 8e-6}) curves.push_back(cell_curve(R"({"law": "sls", "E_inf": 800, "tau": 0.2})", v, curves.size() + 1));
  const Scene s = parse_scene(kCell + std::string(R"({"law": "sls", "E_inf": 320, "tau": 0.5})") + R"(}, "model": "exact"})");
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::E_inf, FitParameter::tau, FitParameter::delta0};
  f.branch = Branch::all;
  for (auto _ : state) benchmark::DoNotOptimize(fit_joint(curves, s, f));
}
BENCHMARK(BM_FitJointThreeSpeeds)->Unit(benchmark::kMillisecond);

// Real curves fitted in time over their whole history (issue #42's map-speed targets): afmformats'
// dwell curves (../shared/data/instrument; skipped without it) - a stress relaxation on a cell
// (pause, extend, 30 s at constant height, retract; 11 935 samples) and a creep on brain tissue
// (3 s at constant force; 9 000 samples) - and JPK's bundled spot3 curve (2 000 samples, no dwell),
// on a 5 um paraboloid (spot3: its 40 nm tip): a power law (E, beta), a standard linear solid (E,
// E_inf, tau) and a fractional SLS (E, beta, tau, E_inf), with delta0 and P0; and, the floor, the
// elastic fit of the same curve's approach.
const char* kDwellIndenter = R"({"indenter": {"shape": "paraboloid", "R": 5e-6}, "medium": {"type": "half_space",
    "E": 1000, "nu": 0.5)";
const char* kSpotIndenter = R"({"indenter": {"shape": "paraboloid", "R": 4e-8}, "medium": {"type": "half_space",
    "E": 1e5, "nu": 0.5)";

CurveData real_curve(const std::string& name, bool* found) {
  const std::string bundled = std::string(LAYERJKR_SOURCE_DIR) + "/data/instrument/" + name;
  const std::string shared = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/" + name;
  const std::string path = std::ifstream(bundled).good() ? bundled : shared;
  *found = std::ifstream(path).good();
  return *found ? to_curve_data(InstrumentReader(path).curve(0), path) : CurveData{};
}

void BM_FitRealInTime(benchmark::State& state, const std::string& name, const std::string& law) {
  bool found = false;
  const CurveData c = real_curve(name, &found);
  if (!found) {
    state.SkipWithError("needs ../shared/data/instrument");
    return;
  }
  const std::string head = name.find("spot3") != std::string::npos ? kSpotIndenter : kDwellIndenter;
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::delta0, FitParameter::P0};
  f.branch = Branch::all;
  std::string scene = head + "}}";
  if (law == "power_law") {
    scene = head + R"(, "viscoelastic": {"law": "power_law", "beta": 0.2, "t0": 1}}})";
    f.free.push_back(FitParameter::beta);
  } else if (law == "sls") {
    scene = head + R"(, "viscoelastic": {"law": "sls", "E_inf": 300, "tau": 1}}})";
    f.free.insert(f.free.end(), {FitParameter::E_inf, FitParameter::tau});
  } else if (law == "fractional_sls") {
    scene = head + R"(, "viscoelastic": {"law": "fractional_sls", "beta": 0.4, "tau": 1, "E_inf": 200}}})";
    f.free.insert(f.free.end(), {FitParameter::beta, FitParameter::tau, FitParameter::E_inf});
  } else {
    f.branch = Branch::approach;  // the elastic floor
  }
  const Scene s = parse_scene(scene);
  for (auto _ : state) benchmark::DoNotOptimize(fit(c, s, f));
  state.counters["samples"] = static_cast<double>(c.size());
}
const char* kRelax = "fmt-jpk-sr_cell1-0008.jpk-force";
const char* kCreep = "fmt-jpk-cc_pr14-brain-2021.06.30.jpk-force";
const char* kSpot = "fmt-jpk-fd_spot3-0192.jpk-force";
BENCHMARK_CAPTURE(BM_FitRealInTime, stress_relaxation_power_law, kRelax, "power_law")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, stress_relaxation_sls, kRelax, "sls")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, stress_relaxation_fractional_sls, kRelax, "fractional_sls")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, stress_relaxation_elastic_floor, kRelax, "elastic")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitRealInTime, creep_power_law, kCreep, "power_law")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, creep_sls, kCreep, "sls")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, creep_fractional_sls, kCreep, "fractional_sls")->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_FitRealInTime, creep_elastic_floor, kCreep, "elastic")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitRealInTime, spot3_power_law, kSpot, "power_law")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitRealInTime, spot3_sls, kSpot, "sls")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitRealInTime, spot3_fractional_sls, kSpot, "fractional_sls")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_FitRealInTime, spot3_elastic_floor, kSpot, "elastic")->Unit(benchmark::kMillisecond);

const char* kElastomer = R"({"indenter": {"shape": "paraboloid", "R": 1e-3}, "medium": {"type": "half_space", "E": 1e6,
    "nu": 0.5}, "w": )";

// Crack kinetics: a 400-sample curve (E, w, v_star, n, delta0 free, from a scene off in w, v_star, n).
void BM_FitKinetic(benchmark::State& state) {
  SimulationOptions o;
  o.max_indentation = 2e-6;
  o.speed = 1e-6;
  o.points_per_branch = 200;
  o.noise = 2e-6;
  o.delta0 = 1e-6;
  const CurveData c = simulate_curve(
      parse_scene(kElastomer + std::string(R"(0.05, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})")), o);
  const Scene s = parse_scene(kElastomer + std::string(R"(0.03, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-5, "n": 0.5}}})"));
  FitOptions f;
  f.free = {FitParameter::E, FitParameter::w, FitParameter::v_star, FitParameter::n, FitParameter::delta0};
  f.branch = Branch::all;
  for (auto _ : state) benchmark::DoNotOptimize(fit(c, s, f));
}
BENCHMARK(BM_FitKinetic)->Unit(benchmark::kMillisecond)->Iterations(1);

// A summary's rate-dependent pull-off: one retract and the sweep of five rates.
void BM_KineticSummary(benchmark::State& state) {
  const Scene s = parse_scene(kElastomer + std::string(R"(0.05, "adhesion": {"kinetics": {"law": "maugis_barquins", "v_star": 1e-6, "n": 0.6}}})"));
  AnswerOptions a;
  a.retract = RetractDrive{RetractControl::fixed_grips, 1e-6, 0.0};
  for (auto _ : state) benchmark::DoNotOptimize(solve_summary(s, a));
}
BENCHMARK(BM_KineticSummary)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
