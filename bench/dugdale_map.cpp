// What a Maugis-Dugdale force map of a film costs (issue 35's target: 64 x 64 in under 5 min on
// 2 threads): the AFM case of bench/dugdale_fit_cost - a 20 nm paraboloid on a 10 nm bonded
// film (nu = 0.3), w = 0.05 J/m^2, sigma0 = 170 MPa - with E varied by +-20 % and w by +-15 %
// across the map, each pixel's retract written by the library's Maugis-Dugdale law (60 radii
// from the pull-off to 15 nm beyond, 30 samples off contact) with fresh 0.5 % noise; each fit
// starts from the map's nominal scene. fit_batch on 1 and 2 threads, E and w free, then E, w and
// sigma0. The film's Dugdale table is built before the clock starts (its cost is printed apart:
// once per medium and machine, then the disk cache).
//
// Run: build/bin/dugdale_map [side = 64]   (prints a markdown table)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "afm_retract.hpp"
#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Scene film(double E, double w) {
  Scene s = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-8},
      "medium": {"type": "layer", "E": 3e9, "nu": 0.3, "h": 1e-8}, "model": "exact",
      "w": 0.05, "adhesion": {"model": "maugis_dugdale", "sigma0": 1.7e8}})",
                        "bench scene");
  s.medium.E = E;
  s.w = w;
  return s;
}

CurveData retract(const Scene& truth, std::mt19937_64& rng) { return bench::afm_retract(truth, rng); }

}  // namespace

int main(int argc, char** argv) {
  const int side = argc > 1 ? std::atoi(argv[1]) : 64;
  if (side < 1) return 2;
  const Scene nominal = film(3e9, 0.05);
  // The table's pieces for every zone a fit on this film reaches, built once (timed apart).
  auto t0 = std::chrono::steady_clock::now();
  {
    std::mt19937_64 rng(1);
    FitOptions o;
    o.branch = Branch::retract;
    o.free = {FitParameter::E, FitParameter::w, FitParameter::sigma0};
    (void)fit(retract(nominal, rng), nominal, o);
  }
  const double cold = since(t0);
  // Sixteen templates; each pixel one of them with fresh noise.
  std::mt19937_64 rng(7);
  std::vector<Scene> truths;
  for (int k = 0; k < 16; ++k) truths.push_back(film(3e9 * (0.8 + 0.4 * (k % 4) / 3.0), 0.05 * (0.85 + 0.3 * (k / 4) / 3.0)));
  std::vector<CurveData> map;
  for (int i = 0; i < side * side; ++i) {
    map.push_back(retract(truths[static_cast<std::size_t>(i) % truths.size()], rng));
    map.back().source = "pixel " + std::to_string(i);
  }
  std::printf("The film's Dugdale table, built cold (once per medium; then the disk cache): %.2f s\n\n", cold);
  std::printf("| free | curves | threads | wall time [s] | per curve [ms] | not converged |\n|---|---|---|---|---|---|\n");
  for (const bool sigma0 : {false, true})
    for (int jobs : {1, 2}) {
      FitOptions o;
      o.branch = Branch::retract;
      o.free = {FitParameter::E, FitParameter::w};
      if (sigma0) o.free.push_back(FitParameter::sigma0);
      BatchOptions b;
      b.jobs = jobs;
      t0 = std::chrono::steady_clock::now();
      const auto items = fit_batch(map, nominal, o, b);
      const double t = since(t0);
      std::size_t failed = 0;
      for (const auto& it : items) failed += (it.ok && it.summary.converged) ? 0 : 1;
      std::printf("| E, w%s | %zu | %d | %.1f | %.2f | %zu |\n", sigma0 ? ", sigma0" : "", map.size(), jobs, t,
                  1e3 * t / static_cast<double>(map.size()), failed);
    }
  return 0;
}
