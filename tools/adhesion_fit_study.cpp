// Fits across the JKR-DMT transition on AFM-like curves: what a Maugis-Dugdale fit recovers
// and how far JKR and DMT fits of the same curves are off. Prints the Markdown table of
// docs/fitting.md ("Adhesion models: JKR, DMT, Maugis-Dugdale"):
//   build/bin/adhesion_fit_study [seeds] [--film]
// The curves: a paraboloid R = 20 nm on a half-space E = 1 GPa, nu = 0.3, w = 0.05 J/m^2, with
// sigma0 set for Maugis' lambda in {0.1, 0.3, 1, 2, 5}; the retract from the closed form
// (maugis_dugdale_half_space) from A_po + 4 down to the load-controlled pull-off (300 samples),
// then 150 samples free of contact; Gaussian force noise 1 % of the pull-off force. Each fit
// frees E and w (and sigma0 for Maugis-Dugdale) and starts from E and sigma0 off by 2x; a second
// table frees the contact point and the baseline too.
// --film: the same tip on a 10 nm film of the same material on a rigid base (model exact, the
// "dugdale" fit family); the curves are the library's Maugis-Dugdale law on the film (the Dugdale
// solver at each sample's radius) from the pull-off to 15 nm beyond (60 samples, 30 free);
// lambda is Maugis' for the film's material as a half-space (the film stiffens the contact and
// its own lambda is larger). Default 5 seeds: a film fit with sigma0 free costs ~10 s.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <boost/math/constants/constants.hpp>

#include "afm_retract.hpp"  // bench/: the retract the Dugdale benchmarks fit
#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

bool g_film = false;  // --film

constexpr double kPi = boost::math::constants::pi<double>();
constexpr double kR = 20e-9, kE = 1e9, kNu = 0.3, kW = 0.05;
const double kEstar = kE / (1.0 - kNu * kNu);

Scene scene(const std::string& adhesion);

// The film's Maugis-Dugdale retract: the law at 60 radii from its pull-off to 15 nm beyond.
CurveData film_retract(double sigma0, double noise, unsigned seed) {
  char json[128];
  std::snprintf(json, sizeof json, R"({"model": "maugis_dugdale", "sigma0": %.17g})", sigma0);
  Scene truth = scene(json);
  truth.medium.E = kE;
  truth.w = kW;
  std::mt19937_64 rng(seed);
  CurveData c = bench::afm_retract(truth, rng, noise);
  c.source = "maugis_dugdale on a film";
  return c;
}

// The pull-off force of the retract's truth [N].
double pull_off_force(double sigma0) {
  if (!g_film) return maugis_dugdale_pull_off(kR, kEstar, kW, sigma0).P;
  const CurveData c = film_retract(sigma0, 0.0, 1);
  return *std::min_element(c.P.begin(), c.P.end());
}

CurveData maugis_retract(double sigma0, double noise, unsigned seed) {
  if (g_film) return film_retract(sigma0, noise, seed);
  const double length = std::cbrt(kPi * kW * kR * kR / (4.0 * kEstar / 3.0));
  const CriticalPoint po = maugis_dugdale_pull_off(kR, kEstar, kW, sigma0);
  const double a_max = po.a + 4.0 * length;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  CurveData c;
  c.source = "maugis_dugdale";
  const std::size_t n = 300;
  for (std::size_t i = 0; i < n; ++i) {
    const AdhesiveState s = maugis_dugdale_half_space(kR, kEstar, kW, sigma0, a_max - (a_max - po.a) * i / (n - 1.0));
    c.delta.push_back(s.delta);
    c.P.push_back(s.P + noise * g(rng));
    c.segment.push_back(1);
  }
  const double span = c.delta.front() - po.delta;
  for (std::size_t i = 1; i <= n / 2; ++i) {
    c.delta.push_back(po.delta - span * i / n);
    c.P.push_back(noise * g(rng));
    c.segment.push_back(1);
  }
  return c;
}

Scene scene(const std::string& adhesion) {
  char b[512];
  if (g_film)
    std::snprintf(b, sizeof b,
                  R"({"indenter": {"shape": "paraboloid", "R": %.17g}, "medium": {"type": "layer", "E": %.17g,
                  "nu": %.17g, "h": 1e-8}, "model": "exact", "adhesion": %s})",
                  kR, 2.0 * kE, kNu, adhesion.c_str());
  else
    std::snprintf(b, sizeof b,
                  R"({"indenter": {"shape": "paraboloid", "R": %.17g}, "medium": {"type": "half_space", "E": %.17g,
                  "nu": %.17g}, "adhesion": %s})",
                  kR, 2.0 * kE, kNu, adhesion.c_str());
  return parse_scene(b, "adhesion_fit_study");
}

struct Tally {
  int n = 0, identifiable = 0;
  int covered[3] = {0, 0, 0}, with_error[3] = {0, 0, 0};
  double ratio_E = 0.0, ratio_w = 0.0, ratio_E2 = 0.0, ratio_w2 = 0.0;
  void add_ratios(double rE, double rw) {
    ++n;
    ratio_E += rE;
    ratio_w += rw;
    ratio_E2 += rE * rE;
    ratio_w2 += rw * rw;
  }
};

// Mean ± standard deviation over the seeds, to four decimals.
std::string mean_sd(double sum, double sum2, int n) {
  const double m = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - m * m));
  char b[64];
  std::snprintf(b, sizeof b, "%.4f ± %.4f", m, sd);
  return b;
}

std::string fraction(int k, int n) { return std::to_string(k) + "/" + std::to_string(n); }

// One table: every fit frees E and w (Maugis-Dugdale also sigma0), and with `offsets` also the
// contact point delta0 and the baseline P0.
void table(int seeds, bool offsets) {
  std::printf("\n%s\n\n", offsets ? "Contact point and baseline free as well (delta0, P0):"
                                   : "Contact point and baseline known (delta0 = P0 = 0 fixed):");
  std::printf("| lambda | sigma0 [MPa] | MD: sigma0 identifiable | MD: E, w, sigma0 within 1.96 SE | "
              "MD: E/E_true | MD: w/w_true | JKR: E/E_true | JKR: w/w_true | DMT: E/E_true | DMT: w/w_true |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const double lambda : {0.1, 0.3, 1.0, 2.0, 5.0}) {
    const double sigma0 = lambda / maugis_lambda(kR, kEstar, kW, 1.0);
    const double noise = 0.01 * std::abs(pull_off_force(sigma0));
    char md_json[128];
    std::snprintf(md_json, sizeof md_json, R"({"model": "maugis_dugdale", "sigma0": %.17g})", 2.0 * sigma0);
    const Scene md = scene(md_json), jkr = scene(R"({"model": "jkr"})"), dmt = scene(R"({"model": "dmt"})");
    Tally t_md, t_jkr, t_dmt;
    for (int seed = 1; seed <= seeds; ++seed) {
      const CurveData c = maugis_retract(sigma0, noise, static_cast<unsigned>(seed));
      FitOptions o;
      o.branch = Branch::retract;
      o.free = {FitParameter::E, FitParameter::w, FitParameter::sigma0};
      if (offsets) o.free.insert(o.free.end(), {FitParameter::delta0, FitParameter::P0});
      const FitSummary s = fit(c, md, o);
      t_md.add_ratios(s[FitParameter::E].value / kE, s[FitParameter::w].value / kW);
      t_md.identifiable += s[FitParameter::sigma0].identifiable ? 1 : 0;
      const double truth[3] = {kE, kW, sigma0};
      for (int k = 0; k < 3; ++k) {
        const ParameterEstimate& e = s.parameters[static_cast<std::size_t>(k)];
        if (!std::isfinite(e.standard_error)) continue;
        ++t_md.with_error[k];
        t_md.covered[k] += std::abs(e.value - truth[k]) <= 1.96 * e.standard_error ? 1 : 0;
      }
      o.free = {FitParameter::E, FitParameter::w};
      if (offsets) o.free.insert(o.free.end(), {FitParameter::delta0, FitParameter::P0});
      const FitSummary j = fit(c, jkr, o);
      t_jkr.add_ratios(j[FitParameter::E].value / kE, j[FitParameter::w].value / kW);
      const FitSummary d = fit(c, dmt, o);
      t_dmt.add_ratios(d[FitParameter::E].value / kE, d[FitParameter::w].value / kW);
    }
    std::printf("| %g | %.4g | %s | %s, %s, %s | %s | %s | %s | %s | %s | %s |\n", lambda, sigma0 / 1e6,
                fraction(t_md.identifiable, seeds).c_str(), fraction(t_md.covered[0], t_md.with_error[0]).c_str(),
                fraction(t_md.covered[1], t_md.with_error[1]).c_str(),
                fraction(t_md.covered[2], t_md.with_error[2]).c_str(),
                mean_sd(t_md.ratio_E, t_md.ratio_E2, t_md.n).c_str(), mean_sd(t_md.ratio_w, t_md.ratio_w2, t_md.n).c_str(),
                mean_sd(t_jkr.ratio_E, t_jkr.ratio_E2, t_jkr.n).c_str(),
                mean_sd(t_jkr.ratio_w, t_jkr.ratio_w2, t_jkr.n).c_str(),
                mean_sd(t_dmt.ratio_E, t_dmt.ratio_E2, t_dmt.n).c_str(),
                mean_sd(t_dmt.ratio_w, t_dmt.ratio_w2, t_dmt.n).c_str());
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 0;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--film")
      g_film = true;
    else
      seeds = std::atoi(argv[i]);
  }
  if (seeds == 0 && argc == 1 + (g_film ? 1 : 0)) seeds = g_film ? 5 : 20;
  if (seeds < 1) {
    std::fprintf(stderr, "adhesion_fit_study: seeds = %s must be a positive integer\n", argv[1]);
    return 2;
  }
  table(seeds, false);
  if (!g_film) table(seeds, true);  // the film: the known contact point only (cost)
  return 0;
}
