// The measured study behind the two-model approach's defaults (issue #14, docs/discrete-data.md):
// synthetic FEM-like data from three models whose truth is known (Winkler, the uniform layer,
// the exact layer; the Appendix A top layer under a 10 mm paraboloid), 20 noise seeds at each
// noise level, both smoothings, both approaches. Printed as markdown tables: the JKR curve's
// error in P and delta over the inner radii, and the pull-off force's, median and 90th
// percentile over seeds, and the replicates that failed to make a model.
//
// Run: build/bin/discrete_study [OUT.md] (target regenerate_discrete_study writes
// docs/data/discrete_study.md; the test generated_discrete_study fails when it is stale)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

constexpr double kR = 10e-3, kW = 0.05;
constexpr double kMesh = 5e-6;  // the convex run's node spacing at the surface: h / 20
const ElasticLayer kLayer{3e6, 0.3, 0.1e-3, Base::bonded};

struct Source {
  const char* name;
  ContactModelPtr model;
};

std::vector<Source> sources() {
  const auto c = thin_layer_constants(kLayer);
  const auto p = make_paraboloid(kR);
  return {{"winkler", make_winkler(p, c.K)}, {"uniform layer", make_uniform_layer(p, kLayer)}, {"exact layer", make_exact_layer(p, kLayer)}};
}

struct Setup {
  int radii = 6;          // flat-punch radii over a/h 1 .. 6
  int convex_steps = 20;  // substeps of the convex run, to a/h 7
};

struct Errors {
  double P = NAN, delta = NAN, pull_off = NAN;  // NaN: the data made no model
};

Errors measure(const ContactModelPtr& truth, const Setup& setup, double noise, unsigned seed, DiscreteApproach approach,
               Smoothing smoothing) {
  std::vector<double> radii;
  for (int k = 0; k < setup.radii; ++k) radii.push_back(kLayer.h * (1.0 + 5.0 * k / (setup.radii - 1)));
  SyntheticSampling flat_sampling{20, 0.025e-3, noise, seed};
  SyntheticSampling convex_sampling{setup.convex_steps, truth->state(7 * kLayer.h).delta_H, noise, seed + 1000,
                                    kMesh};
  DiscreteOptions options;
  options.smoothing = smoothing;
  options.linearity_tolerance = 0.1;
  Errors e;
  try {
    const ConvexData convex = sample_convex(*truth, convex_sampling);
    const ContactModelPtr model = approach == DiscreteApproach::two_models
                                      ? make_discrete_model(sample_flat_punch(*truth, radii, flat_sampling), convex, options)
                                      : make_single_model(convex, options);
    const JkrSolution rebuilt(model, kW), exact(truth, kW);
    double dP = 0, dd = 0, Pmax = 0, dmax = 0;
    for (double a = 2.0 * kLayer.h; a <= 5.5 * kLayer.h; a += 0.05 * kLayer.h) {
      const AdhesiveState s = rebuilt.at(a), t = exact.at(a);
      dP = std::max(dP, std::abs(s.P - t.P)), Pmax = std::max(Pmax, std::abs(t.P));
      dd = std::max(dd, std::abs(s.delta - t.delta)), dmax = std::max(dmax, std::abs(t.delta));
    }
    e.P = dP / Pmax;
    e.delta = dd / dmax;
    const auto po = rebuilt.pull_off(), pt = exact.pull_off();
    if (po && pt) e.pull_off = std::abs(po->P / pt->P - 1.0);
  } catch (const Error& x) {
    if (std::getenv("DISCRETE_STUDY_VERBOSE")) std::fprintf(stderr, "%s\n", x.what());
  }
  return e;
}

struct Stats {
  double median = NAN, p90 = NAN;
  int failed = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  const auto n0 = v.size();
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  s.failed = static_cast<int>(n0 - v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.median = v[v.size() / 2];
  s.p90 = v[std::min(v.size() - 1, static_cast<std::size_t>(0.9 * static_cast<double>(v.size())))];
  return s;
}

std::string pct(const Stats& s) {
  char buf[64];
  if (std::isnan(s.median)) return "fails";
  std::snprintf(buf, sizeof buf, "%.2g / %.2g", 100 * s.median, 100 * s.p90);
  return buf;
}

constexpr int kSeeds = 20;

void table(const char* title, const std::vector<Source>& srcs, const std::vector<double>& noises, const Setup& setup) {
  std::printf("\n### %s\n\n", title);
  std::printf("| source | noise | approach | smoothing | P error %% (median / p90) | delta error %% | pull-off error %% | failed |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const Source& src : srcs)
    for (double noise : noises)
      for (auto approach : {DiscreteApproach::two_models, DiscreteApproach::single_model})
        for (auto smoothing : {Smoothing::log_polynomial, Smoothing::log_spline}) {
          std::vector<double> P, d, po;
          for (unsigned seed = 1; seed <= kSeeds; ++seed) {
            const Errors e = measure(src.model, setup, noise, seed, approach, smoothing);
            P.push_back(e.P), d.push_back(e.delta), po.push_back(e.pull_off);
            if (noise == 0.0) break;  // one noiseless run is every run
          }
          const Stats sP = stats(P), sd = stats(d), spo = stats(po);
          std::printf("| %s | %.1f %% | %s | %s | %s | %s | %s | %d/%zu |\n", src.name, 100 * noise,
                      approach == DiscreteApproach::two_models ? "two models" : "single model",
                      smoothing == Smoothing::log_polynomial ? "log polynomial" : "log B-spline", pct(sP).c_str(),
                      pct(sd).c_str(), pct(spo).c_str(), sP.failed, P.size());
        }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && !std::freopen(argv[1], "w", stdout)) {
    std::fprintf(stderr, "discrete_study: cannot write %s\n", argv[1]);
    return 1;
  }
  const std::vector<Source> srcs = sources();
  std::printf("# The two-model approach, measured (tools/discrete_study.cpp)\n\n");
  std::printf("Truth: a 10 mm paraboloid on the Appendix A top layer (E = 3 MPa, nu = 0.3, h = 0.1 mm, bonded), "
              "w = %.2g J/m^2. Flat punch: 20 load steps to 0.025 mm at radii spread over a/h 1 .. 6; convex: "
              "equal substeps to a/h = 7, the contact radius read off a surface mesh of %.3g um (h/20: the outermost node in contact, as the paper's FEM reads it). Noise: relative, Gaussian, on every force (and nowhere else). Errors of the "
              "JKR curve over a/h 2 .. 5.5: max |P - P_true| / max |P_true| and the same for delta; pull-off: "
              "relative. %d seeds per row (one when noiseless).\n",
              kW, kMesh * 1e6, kSeeds);
  table("Six radii, 20 convex substeps (the paper's sampling)", srcs, {0.0, 0.001, 0.003, 0.01}, Setup{});
  table("Where the flat punch stops helping: 4 radii, 80 convex substeps", {srcs[2]}, {0.0, 0.001, 0.01}, Setup{4, 80});
  table("More radii: 8 radii, 20 convex substeps", {srcs[2]}, {0.001, 0.01}, Setup{8, 20});
  return 0;
}
