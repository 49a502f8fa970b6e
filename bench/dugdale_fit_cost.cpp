// What a Maugis-Dugdale fit on a layer costs (the "dugdale" fit family), against the JKR fit of
// the same curve on the same film (the tabulated family) and Maugis' closed form on a half-space.
//
// How the data is made: the issue's AFM case - a paraboloid R = 20 nm on a 10 nm film (E = 3 GPa,
// nu = 0.3, bonded), w = 0.05 J/m^2, sigma0 = 170 MPa (lambda ~ 0.5) - written by the library's
// Maugis-Dugdale law (or the Dugdale DMT) at 60 radii from the pull-off to 15 nm beyond, 30
// samples off contact, 0.5 % of the pull-off force as Gaussian noise; each fit starts with E 2x
// off (and sigma0 2x off when free). Median of 3 runs. The last rows take a 1 GPa film at
// sigma0 = 256 MPa (lambda ~ 2 for the material as a half-space), where the narrower Dugdale
// zone needs the 61-radius grid. The film's Dugdale table (adhesion/dugdale_table.hpp) is
// built before the rows, on a fresh process without the disk cache, and its cost printed apart:
// once per medium and machine.
//
// Run: LAYERJKR_CACHE=off build/bin/dugdale_fit_cost   (~15 s; prints a markdown table)
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "afm_retract.hpp"
#include "layerjkr/adhesion.hpp"
#include "layerjkr/built_scene.hpp"
#include "layerjkr/contact.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"
#include "median_time.hpp"

using namespace layerjkr;
using layerjkr::bench::median_seconds;

namespace {

std::string film(double E) {
  return R"({"type": "layer", "E": )" + std::to_string(E) + R"(, "nu": 0.3, "h": 1e-8})";
}
const std::string kHalfSpace = R"({"type": "half_space", "E": 3e9, "nu": 0.3})";

Scene scene(const std::string& adhesion, const std::string& medium) {
  const std::string model = medium == kHalfSpace ? "" : R"(, "model": "exact")";
  return parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 2e-8}, "medium": )" + medium + model +
                         R"(, "w": 0.05, "adhesion": )" + adhesion + "}",
                     "bench scene");
}

CurveData curve_of(const Scene& truth) {
  std::mt19937_64 rng(1);
  return bench::afm_retract(truth, rng);
}

void row(const char* what, const CurveData& c, Scene start, std::vector<FitParameter> free, int runs) {
  start.medium.E *= 2.0;
  if (start.adhesion.sigma0 && free.size() > 2) *start.adhesion.sigma0 *= 2.0;
  FitOptions o;
  o.branch = Branch::retract;
  o.free = std::move(free);
  FitSummary s;
  const double t = median_seconds([&] { s = fit(c, start, o); }, runs);
  std::string grid = "-";  // the dugdale family's radii, from its note
  const std::string key = "solved per parameter vector on ";
  for (const std::string& line : s.notices)
    if (line.find(key) != std::string::npos) grid = std::to_string(std::stoi(line.substr(line.find(key) + key.size())));
  std::string sigma0;
  for (const ParameterEstimate& p : s.parameters)
    if (p.parameter == FitParameter::sigma0) sigma0 = ", sigma0 " + std::to_string(p.value / 1e6).substr(0, 5) + " MPa";
  std::printf("| %s | %s | %s | %d | %.3g s%s | E %.4g, w %.4g%s |\n", what, s.model.c_str(), grid.c_str(),
              s.iterations, t, runs == 1 ? " (1 run)" : "", s[FitParameter::E].value, s[FitParameter::w].value,
              sigma0.c_str());
}

}  // namespace

int main() {
  const std::string md = R"({"model": "maugis_dugdale", "sigma0": 1.7e8})";
  const std::string dmt = R"({"model": "dmt", "sigma0": 1.7e8})";
  const Scene md_film = (scene(md, film(3e9)));
  const CurveData c = curve_of(md_film);
  const CurveData c_dmt = curve_of((scene(dmt, film(3e9))));
  const CurveData c_half = curve_of(scene(md, kHalfSpace));
  {
    const auto t0 = std::chrono::steady_clock::now();
    FitOptions o;
    o.branch = Branch::retract;
    o.free = {FitParameter::E, FitParameter::w, FitParameter::sigma0};
    Scene start = md_film;
    start.medium.E *= 2.0;
    *start.adhesion.sigma0 *= 2.0;
    (void)fit(c, start, o);
    std::printf("The film's Dugdale table, built by a first fit of E, w and sigma0: %.2f s (fit included)\n\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::printf("| fit (truth w = 0.05 J/m^2) | model | grid radii | iterations | time | result |\n"
              "|---|---|---|---|---|---|\n");
  row("JKR on the film, E w", c, (scene(R"({"model": "jkr"})", film(3e9))), {FitParameter::E, FitParameter::w}, 3);
  row("Maugis-Dugdale on the film, E w", c, md_film, {FitParameter::E, FitParameter::w}, 3);
  row("Maugis-Dugdale on the film, E w sigma0", c, md_film,
      {FitParameter::E, FitParameter::w, FitParameter::sigma0}, 3);
  row("Dugdale DMT on the film, E w", c_dmt, (scene(dmt, film(3e9))), {FitParameter::E, FitParameter::w}, 3);
  row("Maugis-Dugdale on the half-space (closed form), E w", c_half, scene(md, kHalfSpace),
      {FitParameter::E, FitParameter::w}, 3);
  const std::string md2 = R"({"model": "maugis_dugdale", "sigma0": 2.564e8})";
  const Scene stiff = scene(md2, film(1e9));
  const CurveData c2 = curve_of(stiff);
  row("1 GPa film, sigma0 256 MPa: Maugis-Dugdale, E w", c2, stiff, {FitParameter::E, FitParameter::w}, 3);
  row("1 GPa film, sigma0 256 MPa: Maugis-Dugdale, E w sigma0", c2, stiff,
      {FitParameter::E, FitParameter::w, FitParameter::sigma0}, 3);
  return 0;
}
