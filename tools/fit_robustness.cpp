// Does a fit depend on luck? Synthetic curves of the families users measure, each fitted under
// many noise draws and from starts 0.1x to 10x off, counted as: within 3 standard errors of the
// truth in every free parameter ("right"), declared failed (not converged, or not identifiable),
// or stated with confidence and wrong - a bug. Prints the Markdown table of docs/benchmarks.md
// ("Fits that never depend on luck"):
//   build/bin/fit_robustness [--draws N] [--family NAME] [--verbose] [OUT.md]
// OUT.md receives the counts (docs/data/fit_robustness.md); the time per fit goes to standard
// output with them. FIT_ROBUSTNESS_DUMP=DIR also writes each curve to DIR as delta,P,segment CSV.
// Default 25 noise draws x 5 starts per case (2 250 fits, about 15 s on one core). A wrong
// answer of 3-5 standard errors is counted apart from one beyond 5: with Gaussian noise 0.27 %
// of parameters fall beyond 3 by chance, none beyond 5. A line under the table says how the
// error bars are calibrated: the fractions of estimates beyond 1, 2 and 3 of them.
//
// The families (the truth is the library's own adhesive law, each sample's radius found by
// bisection on its delta(a) along the stable branch; samples even in delta):
//   afm         approach from free samples to the turning point (5x the pull-off force), retract to the load-controlled
//               pull-off then free samples: a soft lever's snap-off. Free E, w, delta0, P0; noise
//               0.5 % of the pull-off force; baseline offset 3 noise sigmas; contact point shifted.
//   stiff_lever the same, but the retract follows the branch past the pull-off until the lever of
//               stiffness k lets go (dP/d delta = -k), k given as an instrument file carries it.
//   rig         a JKR rig: loading from zero load, unloading past the pull-off to just above the
//               fixed-grips limit, every sample in contact, no baseline; free E, w, delta0;
//               force noise 0.2 % of the pull-off, displacement noise 1 % of the span; fitted with
//               errors in both variables, both noises estimated (FitOptions::errors_in_displacement;
//               FIT_ROBUSTNESS_LEAST_SQUARES=1 fits least squares in the force instead).
//   rig_Pa      the same rig as load against contact radius (no displacement); free E, w.
//   tension     unloading only, from 0.74 of the pull-off through it, then a necking tail
//               relaxing to zero without a jump; free E, w, delta0.
// Media: a sphere on a half-space, on a bonded film (exact layer; a/h up to 2-4.5), on a thin
// incompressible bonded film (a/h >= 5), on a thin compressible film (two-term, nu 0.3, where the
// expansion holds) and on a two-layer stack (not the tension family: a stack's shape changes with
// depth).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <glog/logging.h>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

struct Medium {
  std::string name;
  std::string json;  // the scene's medium and model keys, E replaced by %E%
  double R;          // sphere radius [m]
  double a_max;      // the largest radius of the truth's grid [m]; the turning point lies below it
};

std::string replace(std::string s, const std::string& key, const std::string& value) {
  for (std::size_t p; (p = s.find(key)) != std::string::npos;) s.replace(p, key.size(), value);
  return s;
}

Scene make_scene(const Medium& m, double E, double w) {
  // A stack's moduli scale together in the fit: its second layer is always 10x the first.
  const std::string json = replace(replace(m.json, "%E10%", format_double(10.0 * E)), "%E%", format_double(E));
  return parse_scene(replace(json, "%w%", format_double(w)), m.name);
}

// The stable branch on a grid of radii (delta and P), where it starts and ends, and the law that
// gives every sample its exact state.
struct StableBranch {
  AdhesiveLawPtr law;
  std::vector<double> a, P, delta;
  std::size_t grips = 0;     // min delta: the fixed-grips limit
  std::size_t pull_off = 0;  // min P: the load-controlled pull-off
  std::size_t zero = 0;      // P = 0 on the stable branch: where the approach snaps in
  double stiffness_at(std::size_t j) const {  // dP/d delta between j and j + 1
    return (P[j + 1] - P[j]) / (delta[j + 1] - delta[j]);
  }
};

StableBranch branch(const Scene& s, double a_max) {
  const BuiltScene built = build_scene(s, 0.0, false);
  StableBranch b;
  b.law = make_adhesive_law(built.model, resolve_model(s).spec, s.w, s.adhesion);
  for (int k = 0; k <= 2000; ++k) {
    const AdhesiveState st = b.law->at(a_max * (0.002 + 0.998 * k / 2000.0));
    b.a.push_back(st.a);
    b.P.push_back(st.P);
    b.delta.push_back(st.delta);
  }
  b.grips = static_cast<std::size_t>(std::min_element(b.delta.begin(), b.delta.end()) - b.delta.begin());
  b.pull_off = static_cast<std::size_t>(std::min_element(b.P.begin(), b.P.end()) - b.P.begin());
  for (std::size_t j = b.pull_off + 1; j < b.P.size(); ++j)
    if (b.P[j - 1] < 0.0 && b.P[j] >= 0.0) b.zero = j;
  if (b.zero == 0 || b.zero + 100 > b.P.size()) throw InputError("the turning point lies below zero load: raise a_max");
  return b;
}

// The exact state at indentation d on the stable branch between grid indices lo < hi (delta
// grows with a there): bisection on the law's delta(a) to a few ulps.
AdhesiveState on_branch(const StableBranch& b, std::size_t lo, std::size_t hi, double d) {
  std::size_t j = lo;
  while (j + 1 < hi && b.delta[j + 1] < d) ++j;
  double a_lo = b.a[j], a_hi = b.a[j + 1];
  for (int it = 0; it < 200 && a_hi - a_lo > 4e-16 * a_hi; ++it) {
    const double mid = 0.5 * (a_lo + a_hi);
    (b.law->at(mid).delta < d ? a_lo : a_hi) = mid;
  }
  return b.law->at(0.5 * (a_lo + a_hi));
}

struct Truth {
  double E, w;
};

struct Case {
  std::string family;
  const Medium* medium;
  CurveData curve;
  std::vector<FitParameter> free;
  double delta0 = 0.0, P0 = 0.0;  // the offsets put into the data
};

// Samples n points even in delta from radius index `from` to `to` along the branch.
void sample(const StableBranch& b, std::size_t from, std::size_t to, int n, int segment, double noise,
            double d_noise, std::mt19937_64& rng, CurveData* c, bool with_radius = false) {
  std::normal_distribution<double> g(0.0, 1.0);
  const double d0 = b.delta[from], d1 = b.delta[to];
  const std::size_t lo = std::min(from, to), hi = std::max(from, to);
  for (int k = 0; k < n; ++k) {
    const double d = d0 + (d1 - d0) * k / (n - 1.0);
    const AdhesiveState st = on_branch(b, lo, hi, d);
    c->delta.push_back(d + d_noise * g(rng));
    c->P.push_back(st.P + noise * g(rng));
    if (with_radius) c->a.push_back(st.a);
    c->segment.push_back(segment);
  }
}

void free_samples(double d_from, double d_to, int n, int segment, double noise, std::mt19937_64& rng,
                  CurveData* c) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    c->delta.push_back(d_from + (d_to - d_from) * k / (n - 1.0));
    c->P.push_back(noise * g(rng));
    c->segment.push_back(segment);
  }
}

// The lowest radius index a lever of stiffness k holds: dP/d delta = -k below the pull-off.
std::size_t lever_release(const StableBranch& b, double k) {
  std::size_t j = b.pull_off;
  while (j > b.grips + 1 && b.stiffness_at(j - 1) > -k) --j;
  return j;
}

Case make_case(const std::string& family, const Medium& m, const Truth& t, std::mt19937_64& rng) {
  const Scene s = make_scene(m, t.E, t.w);
  const StableBranch b = branch(s, m.a_max);
  Case c;
  c.family = family;
  c.medium = &m;
  c.curve.source = family + " " + m.name;
  // The turning point: where the force first reaches 5x the pull-off force (an AFM curve's
  // force range), or the grid's end.
  std::size_t top = b.zero;
  while (top + 1 < b.a.size() && b.P[top] < -5.0 * b.P[b.pull_off]) ++top;
  const double pull_off = -b.P[b.pull_off];
  const double span = b.delta[top] - b.delta[b.grips];
  if (family == "afm" || family == "stiff_lever") {
    const double noise = 0.005 * pull_off;
    c.free = {FitParameter::E, FitParameter::w, FitParameter::delta0, FitParameter::P0};
    free_samples(b.delta[b.zero] - 0.5 * span, b.delta[b.zero], 60, 0, noise, rng, &c.curve);
    sample(b, b.zero, top, 140, 0, noise, 0.0, rng, &c.curve);
    std::size_t release = b.pull_off;
    if (family == "stiff_lever") {
      // A lever 0.3 x as stiff as the contact at the turning point: the tip goes well past the
      // pull-off before it lets go.
      const double k = 0.3 * b.stiffness_at(top - 1);
      c.curve.spring_constant = k;
      release = lever_release(b, k);
    }
    sample(b, top, release, 140, 1, noise, 0.0, rng, &c.curve);
    free_samples(b.delta[release] - 0.02 * span, b.delta[release] - 0.5 * span, 60, 1, noise, rng, &c.curve);
    c.delta0 = 0.1 * span;
    c.P0 = 3.0 * noise;
  } else if (family == "rig" || family == "rig_Pa") {
    const double noise = 0.002 * pull_off;
    // Unloading ends a tenth of the way from the grips limit back to the pull-off (in radius).
    const std::size_t end = b.grips + (b.pull_off - b.grips) / 10 + 1;
    const bool Pa = family == "rig_Pa";
    sample(b, b.zero, top, 150, 0, noise, Pa ? 0.0 : 0.01 * span, rng, &c.curve, Pa);
    sample(b, top, end, 150, 1, noise, Pa ? 0.0 : 0.01 * span, rng, &c.curve, Pa);
    if (Pa) {
      c.curve.delta.clear();
      c.free = {FitParameter::E, FitParameter::w};
    } else {
      c.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
      c.delta0 = 0.05 * span;
    }
  } else if (family == "tension") {
    const double noise = 0.003 * pull_off;
    std::size_t start = b.pull_off;
    while (start < top && b.P[start] < -0.74 * pull_off) ++start;
    sample(b, start, b.pull_off, 45, 1, noise, 0.0, rng, &c.curve);
    std::normal_distribution<double> g(0.0, noise);
    const double d_end = b.delta[b.pull_off], step = (b.delta[start] - d_end) / 44.0;
    for (int k = 1; k <= 15; ++k) {
      c.curve.delta.push_back(d_end - step * k);
      c.curve.P.push_back(-pull_off * std::exp(-k / 4.0) + g(rng));
      c.curve.segment.push_back(1);
    }
    c.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  }
  for (double& d : c.curve.delta) d += c.delta0;
  for (double& p : c.curve.P) p += c.P0;
  return c;
}

enum class Outcome { right, declared, wrong_3_5, wrong_5 };

struct Tally {
  int fits = 0, right = 0, declared = 0, wrong_3_5 = 0, wrong_5 = 0, threw = 0;
  double seconds = 0.0;
  /// Fits beyond 3 standard errors that honest Gaussian error bars give by chance: per fit not
  /// declared failed, 1 - (1 - 0.0027)^p for its p parameters.
  double chance_beyond_3 = 0.0;
};

// Each case's noise draws from a seed of its own (FNV-1a of "family | medium", then the draw):
// with one seed per draw shared by every case, one unlucky realisation counted once per medium.
std::uint64_t case_seed(const std::string& key, int draw) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : key) h = (h ^ ch) * 1099511628211ull;
  return (h ^ static_cast<std::uint64_t>(draw)) * 1099511628211ull;
}

bool g_verbose = false;
constexpr double kGaussianBeyond3 = 0.0026998;  // P(|z| > 3) for a standard normal

// The error bars' calibration: of the parameters of fits not declared failed, how many lie beyond
// 1, 2 and 3 standard errors of the truth (Gaussian: 31.7 %, 4.55 %, 0.27 %).
struct Calibration {
  long parameters = 0, beyond[3] = {0, 0, 0};
  double signed_z = 0.0, z2 = 0.0;  // sums of (estimate - truth) / SE and its square
};
Calibration g_calibration;
// With --verbose, the same per row and parameter ("family | medium | E"), printed at the end.
std::map<std::string, Calibration> g_row_calibration;
std::string g_row;

Outcome judge(const Case& c, const Truth& t, const FitSummary& s, double* worst) {
  *worst = 0.0;
  for (const ParameterEstimate& e : s.parameters) {
    double truth = 0.0;
    switch (e.parameter) {
      case FitParameter::E: truth = t.E; break;
      case FitParameter::w: truth = t.w; break;
      case FitParameter::delta0: truth = c.delta0; break;
      case FitParameter::P0: truth = c.P0; break;
      default: continue;
    }
    const double z = std::abs(e.value - truth) / e.standard_error;
    if (g_verbose && z > 3.0) std::fprintf(stderr, "  %s: %.3g standard errors\n", to_string(e.parameter), z);
    *worst = std::max(*worst, std::isfinite(z) ? z : INFINITY);
  }
  const bool declared = !s.converged || !s.identifiable;
  if (!declared)
    for (const ParameterEstimate& e : s.parameters) {
      const double truth = e.parameter == FitParameter::E    ? t.E
                           : e.parameter == FitParameter::w  ? t.w
                           : e.parameter == FitParameter::delta0 ? c.delta0
                                                               : c.P0;
      const double z = std::abs(e.value - truth) / e.standard_error;
      ++g_calibration.parameters;
      for (int k = 0; k < 3; ++k) g_calibration.beyond[k] += z > k + 1.0 ? 1 : 0;
      if (g_verbose) {
        Calibration& r = g_row_calibration[g_row + " | " + to_string(e.parameter)];
        ++r.parameters;
        r.signed_z += (e.value - truth) / e.standard_error;
        r.z2 += z * z;
        for (int k = 0; k < 3; ++k) r.beyond[k] += z > k + 1.0 ? 1 : 0;
      }
    }
  if (*worst <= 3.0) return Outcome::right;
  if (declared) return Outcome::declared;
  return *worst <= 5.0 ? Outcome::wrong_3_5 : Outcome::wrong_5;
}

}  // namespace

int main(int argc, char** argv) {
  FLAGS_minloglevel = google::GLOG_FATAL;  // Ceres' internal diagnostics; each fit reports its own
  int draws = 25;
  bool one_start = false;  // only the truth as the start: many draws, to measure the error bars
  std::string only, out;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--family" && i + 1 < argc) only = argv[++i];
    else if (arg == "--verbose") g_verbose = true;
    else if (arg == "--draws" && i + 1 < argc) draws = std::atoi(argv[++i]);
    else if (arg == "--one-start") one_start = true;
    else out = arg;
  }
  if (draws < 1) {
    std::fprintf(stderr, "fit_robustness: draws must be >= 1\n");
    return 2;
  }
  const std::string sphere = R"({"indenter": {"shape": "paraboloid", "R": %R%}, )";
  const auto medium = [&](const std::string& name, double R, const std::string& body, double a_max) {
    return Medium{name, replace(sphere, "%R%", format_double(R)) + body + R"(, "w": %w%})", R, a_max};
  };
  // AFM: a 10 um sphere on a soft gel (E 20 kPa, w 1e-4 J/m^2: zero-load radius 3.8 um on the half-space); rigs: a 5 mm sphere on PDMS.
  const std::vector<Medium> afm_media{
      medium("half-space", 1e-5, R"("medium": {"type": "half_space", "E": %E%, "nu": 0.49})", 8e-6),
      medium("film (exact, h 1 um)", 1e-5, R"("medium": {"type": "layer", "E": %E%, "nu": 0.49, "h": 1e-6, "base": "bonded"}, "model": "exact")", 8e-6),
      medium("film (incompressible, h 0.2 um)", 1e-5, R"("medium": {"type": "layer", "E": %E%, "nu": 0.5, "h": 2e-7, "base": "bonded"}, "model": "incompressible")", 8e-6),
      medium("film (two-term, nu 0.3, h 0.5 um)", 1e-5, R"("medium": {"type": "layer", "E": %E%, "nu": 0.3, "h": 5e-7, "base": "bonded"}, "model": "two_term")", 8e-6),
      medium("stack (1 um on 10 um 10x stiffer)", 1e-5, R"("medium": {"type": "layers", "layers": [{"E": %E%, "nu": 0.49, "h": 1e-6}, {"E": %E10%, "nu": 0.3, "h": 1e-5}], "base": "bonded"}, "model": "exact")", 8e-6)};
  const std::vector<Medium> rig_media{
      medium("half-space", 5e-3, R"("medium": {"type": "half_space", "E": %E%, "nu": 0.49})", 4e-4),
      medium("film (exact, h 100 um)", 5e-3, R"("medium": {"type": "layer", "E": %E%, "nu": 0.49, "h": 1e-4, "base": "bonded"}, "model": "exact")", 4.5e-4)};
  const Truth afm_truth{2e4, 1e-4}, rig_truth{1e6, 0.05};
  const std::vector<double> starts = one_start ? std::vector<double>{1.0} : std::vector<double>{0.1, 0.3, 1.0, 3.0, 10.0};
  struct Plan {
    std::string family;
    const std::vector<Medium>* media;
    Truth truth;
  };
  const std::vector<Plan> plans{{"afm", &afm_media, afm_truth},
                                {"stiff_lever", &afm_media, afm_truth},
                                {"rig", &rig_media, rig_truth},
                                {"rig_Pa", &rig_media, rig_truth},
                                {"tension", &afm_media, afm_truth}};
  std::map<std::string, Tally> rows;
  std::vector<std::string> order;
  Tally total;
  for (const Plan& plan : plans) {
    if (!only.empty() && plan.family != only) continue;
    for (const Medium& m : *plan.media) {
      if (plan.family == "tension" && m.name.rfind("stack", 0) == 0) continue;
      const std::string key = plan.family + " | " + m.name;
      order.push_back(key);
      g_row = key;
      Tally& row = rows[key];
      for (int d = 0; d < draws; ++d) {
        std::mt19937_64 rng(case_seed(key, d));
        Case c;
        try {
          c = make_case(plan.family, m, plan.truth, rng);
        } catch (const Error& e) {
          std::fprintf(stderr, "%s: cannot make the curve: %s\n", key.c_str(), e.what());
          return 1;
        }
        if (std::getenv("FIT_ROBUSTNESS_DUMP")) {
          const std::string path = std::string(std::getenv("FIT_ROBUSTNESS_DUMP")) + "/" + plan.family + "_" + std::to_string(&m - plan.media->data()) + "_" + std::to_string(d) + ".csv";
          if (FILE* f = std::fopen(path.c_str(), "w")) {
            std::fprintf(f, "delta,P,segment\n");
            for (std::size_t i = 0; i < c.curve.P.size(); ++i)
              std::fprintf(f, "%.17g,%.17g,%d\n", c.curve.delta.empty() ? c.curve.a[i] : c.curve.delta[i], c.curve.P[i], c.curve.segment[i]);
            std::fclose(f);
          }
        }
        for (double f : starts) {
          FitOptions o;
          o.free = c.free;
          o.branch = plan.family == "tension" ? Branch::retract : Branch::all;
          // A rig's displacement sensor has noise of its own: errors in both variables, both noises
          // estimated from the data (FIT_ROBUSTNESS_LEAST_SQUARES=1: least squares in the force).
          o.errors_in_displacement = plan.family == "rig" && !std::getenv("FIT_ROBUSTNESS_LEAST_SQUARES");
          const auto t0 = std::chrono::steady_clock::now();
          ++row.fits;
          try {
            const FitSummary s = fit(c.curve, make_scene(m, plan.truth.E * f, plan.truth.w * f), o);
            double worst = 0.0;
            if (s.converged && s.identifiable)
              row.chance_beyond_3 += 1.0 - std::pow(1.0 - kGaussianBeyond3, static_cast<double>(s.parameters.size()));
            switch (judge(c, plan.truth, s, &worst)) {
              case Outcome::right: ++row.right; break;
              case Outcome::declared: ++row.declared; break;
              case Outcome::wrong_3_5: ++row.wrong_3_5; break;
              case Outcome::wrong_5: ++row.wrong_5; break;
            }
            if (g_verbose && worst > 3.0)
              std::fprintf(stderr, "%s draw %d start %gx: %.3g standard errors\n%s\n", key.c_str(), d, f, worst,
                           s.brief_report().c_str());
          } catch (const Error& e) {
            ++row.threw;  // refused: declared, with its reason
            if (g_verbose) std::fprintf(stderr, "%s draw %d start %gx: refused: %s\n", key.c_str(), d, f, e.what());
          }
          row.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
      }
    }
  }
  // The counts (the committed docs/data/fit_robustness.md, checked by generated_fit_robustness) to
  // `out`, or standard output; the time per fit, which varies, to standard output only.
  std::string table = "| family | medium | fits | within 3 SE | declared failed or refused | wrong, 3-5 SE | wrong, > 5 SE |\n"
                      "|---|---|---:|---:|---:|---:|---:|\n";
  std::string times = "| family | medium | mean ms per fit |\n|---|---|---:|\n";
  char line[512];
  for (const std::string& key : order) {
    const Tally& r = rows.at(key);
    const std::size_t bar = key.find(" | ");
    const std::string family = key.substr(0, bar), medium_name = key.substr(bar + 3);
    std::snprintf(line, sizeof line, "| %s | %s | %d | %d | %d | %d | %d |\n", family.c_str(), medium_name.c_str(), r.fits,
                  r.right, r.declared + r.threw, r.wrong_3_5, r.wrong_5);
    table += line;
    std::snprintf(line, sizeof line, "| %s | %s | %.1f |\n", family.c_str(), medium_name.c_str(), 1e3 * r.seconds / r.fits);
    times += line;
    total.fits += r.fits;
    total.right += r.right;
    total.declared += r.declared + r.threw;
    total.wrong_3_5 += r.wrong_3_5;
    total.wrong_5 += r.wrong_5;
    total.seconds += r.seconds;
    total.chance_beyond_3 += r.chance_beyond_3;
  }
  std::snprintf(line, sizeof line, "| **all** | | %d | %d | %d | %d | %d |\n", total.fits, total.right, total.declared,
                total.wrong_3_5, total.wrong_5);
  table += line;
  std::snprintf(line, sizeof line,
                "\nBy chance alone, honest Gaussian error bars put %.1f of these fits beyond 3 standard errors (per fit "
                "not declared failed, 1 - (1 - 0.0027)^p for its p parameters); %d are.\n",
                total.chance_beyond_3, total.wrong_3_5 + total.wrong_5);
  table += line;
  const Calibration& cal = g_calibration;
  const auto percent = [&](int k) { return 100.0 * static_cast<double>(cal.beyond[k]) / std::max(cal.parameters, 1L); };
  std::snprintf(line, sizeof line,
                "\nError bars: of the %ld parameters of fits not declared failed, %.1f %% lie beyond 1 standard error "
                "of the truth, %.2f %% beyond 2 and %.2f %% beyond 3 (Gaussian: 31.7 %%, 4.55 %%, 0.27 %%).\n",
                cal.parameters, percent(0), percent(1), percent(2));
  table += line;
  std::snprintf(line, sizeof line, "| **all** | | %.1f |\n", 1e3 * total.seconds / std::max(total.fits, 1));
  times += line;
  if (out.empty()) {
    std::fputs(table.c_str(), stdout);
  } else if (FILE* f = std::fopen(out.c_str(), "w")) {
    std::fputs(table.c_str(), f);
    std::fclose(f);
  } else {
    std::fprintf(stderr, "fit_robustness: cannot write %s\n", out.c_str());
    return 2;
  }
  std::fputs(("\n" + times).c_str(), stdout);
  for (const auto& [row, c] : g_row_calibration)
    std::fprintf(stderr, "%s: %ld estimates, mean z %+.2f, rms z %.2f, %.1f %% beyond 1 SE, %.2f %% beyond 2, %.2f %% beyond 3\n", row.c_str(),
                 c.parameters, c.signed_z / static_cast<double>(c.parameters), std::sqrt(c.z2 / static_cast<double>(c.parameters)), 100.0 * static_cast<double>(c.beyond[0]) / static_cast<double>(c.parameters),
                 100.0 * static_cast<double>(c.beyond[1]) / static_cast<double>(c.parameters),
                 100.0 * static_cast<double>(c.beyond[2]) / static_cast<double>(c.parameters));
  return total.wrong_5 > 0 ? 1 : 0;
}
