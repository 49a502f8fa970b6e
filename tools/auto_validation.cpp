// What this teaches: whether model "auto" can be trusted - on 200 random scenes, does its
// error estimate bound the real error, and is its choice the cheapest model that is really
// within the tolerance?
//
// How the data is made: nothing is measured. Each scene draws (seeded, reproducible) a
// profile (paraboloid, sphere, cone, power law r^d with d in [1.2, 4], a table sampled from
// a sphere, a callable blunted paraboloid r^2/(2R) + c r^4), nu (a fifth at 1/2, two fifths
// in [0.45, 0.5), the rest in [0, 0.45)), a base (a fifth frictionless), a target pull-off
// radius a/h in [0.5, 60] and a work of adhesion spread over four decades around the one
// that puts Winkler's pull-off there, and a tolerance in {0.3, 1, 3, 10} %. "auto" chooses
// for a summary (choose_layer_model_for_summary, as `layerjkr summary` does). The truth is
// a finer exact layer (20 nodes on 2.5 h panels, no tables: an independent discretisation):
// the real error of a model is that of its pull-off force and zero-load radius against the
// truth's.
//
// Run: build/bin/auto_validation CSV_FILE > SUMMARY.md  (about 10 minutes on 2 cores)
// `cmake --build build --target regenerate_auto_validation` rewrites
// docs/data/auto_validation.{csv,md}.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "layerjkr/callable_profile.hpp"
#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

struct RandomScene {
  std::string kind;
  ProfilePtr profile;
  ElasticLayer layer;
  double w = 0.0, tolerance = 0.0, target = 0.0;
};

RandomScene draw(std::mt19937& rng, int index) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  RandomScene s;
  const double pick = u(rng);
  const double nu = pick < 0.2 ? 0.5 : pick < 0.6 ? 0.45 + 0.0499 * u(rng) : 0.45 * u(rng);
  s.layer = {1.0, nu, 1.0, u(rng) < 0.2 ? Base::frictionless : Base::bonded};
  s.target = std::exp(std::log(0.5) + u(rng) * std::log(120.0));  // a/h in [0.5, 60]
  const double R = s.target * (5.0 + 45.0 * u(rng));
  switch (index % 6) {
    case 0: s.kind = "paraboloid"; s.profile = make_paraboloid(R); break;
    case 1: s.kind = "sphere"; s.profile = make_sphere(R); break;
    case 2: s.kind = "cone"; s.profile = make_cone((40.0 + 45.0 * u(rng)) * M_PI / 180.0); break;
    case 3: {
      const double d = 1.2 + 2.8 * u(rng);
      s.kind = "power_law";
      s.profile = make_power_law(0.5 / (R * std::pow(s.target, d - 2.0)), d);  // ~ paraboloid at the target
      break;
    }
    case 4: {
      std::vector<double> r, z;
      for (int i = 0; i <= 24; ++i) {
        const double x = 0.9 * R * i / 24.0;
        r.push_back(x);
        z.push_back(R - std::sqrt(R * R - x * x));
      }
      s.kind = "table";
      s.profile = make_table_profile(r, z);
      break;
    }
    default: {
      const double c = 0.3 / (R * s.target * s.target);
      s.kind = "callable";
      s.profile = make_callable_profile([R, c](auto r) { return r * r / (2.0 * R) + c * r * r * r * r; }, R);
    }
  }
  const double K = thin_layer_constants({1.0, std::min(nu, 0.49), 1.0, s.layer.base}).K;
  s.w = K * std::pow(s.target, 4) / (8.0 * R * R) * std::pow(10.0, 4.0 * u(rng) - 2.0);
  const double tolerances[] = {0.003, 0.01, 0.03, 0.1};
  s.tolerance = tolerances[static_cast<int>(4 * u(rng)) % 4];
  return s;
}

struct Truth {
  std::optional<CriticalPoint> pull_off;
  std::optional<double> zero_load;
};

double real_error(const ContactSummary& s, const Truth& t) {
  double e = 0.0;
  if (s.pull_off && t.pull_off) e = std::max(e, std::abs(s.pull_off->P / t.pull_off->P - 1.0));
  if (s.pull_off.has_value() != t.pull_off.has_value()) e = INFINITY;
  if (s.zero_load_radius && t.zero_load && *t.zero_load > 0.0)
    e = std::max(e, std::abs(*s.zero_load_radius / *t.zero_load - 1.0));
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: auto_validation CSV_FILE > SUMMARY.md\n");
    return 2;
  }
  std::ofstream csv(argv[1]);
  csv << "scene,profile,nu,base,target_a_over_h,w,tolerance,chosen,estimate,real_error,bounded,"
         "cheapest_within_tolerance,cheapest\n";
  csv.precision(5);
  std::mt19937 rng(20261123);
  const int count = 200;
  int bounded = 0, cheapest = 0, failed = 0;
  double worst_ratio = 0.0;
  std::map<std::string, int> chosen;
  for (int i = 0; i < count; ++i) {
    const RandomScene s = draw(rng, i);
    try {
      ExactLayerOptions fine;
      fine.points_per_panel = 20;
      fine.panel_width = 2.5;
      fine.tabulate_power_laws = false;
      fine.estimate_error = false;
      const JkrSolution truth_solution(make_exact_layer(s.profile, s.layer, fine), s.w);
      const Truth truth{truth_solution.pull_off(), truth_solution.zero_load_radius()};
      const ModelChoice c = choose_layer_model_for_summary(s.profile, s.layer, s.w, s.tolerance);
      const double real = real_error(summarize(JkrSolution(c.contact_model, s.w)), truth);
      // The cheapest model really within tolerance, by the truth.
      std::string best = "exact";
      for (ModelKind kind : layer_model_candidates(s.layer)) {
        try {
          const ContactModelPtr m = make_contact_model(s.profile, layer_model_spec(kind, s.layer));
          if (real_error(summarize(JkrSolution(m, s.w)), truth) <= s.tolerance) {
            best = to_string(kind);
            break;
          }
        } catch (const Error&) {  // a candidate that cannot reach the scene's radii
        }
      }
      const std::string chosen_name = to_string(c.model);
      const bool ok = real <= c.estimated_error;
      bounded += ok;
      cheapest += best == chosen_name;
      ++chosen[chosen_name];
      if (c.estimated_error > 0.0) worst_ratio = std::max(worst_ratio, real / c.estimated_error);
      csv << i << ',' << s.kind << ',' << s.layer.nu << ',' << (s.layer.base == Base::bonded ? "bonded" : "frictionless")
          << ',' << s.target << ',' << s.w << ',' << s.tolerance << ',' << chosen_name << ',' << c.estimated_error << ','
          << real << ',' << ok << ',' << best << ',' << (best == chosen_name) << '\n';
      std::fprintf(stderr, "%3d %-10s nu=%.3f %-12s a/h~%6.2f tol=%.3f -> %-15s est %.2e real %.2e%s\n", i,
                   s.kind.c_str(), s.layer.nu, s.layer.base == Base::bonded ? "bonded" : "frictionless", s.target,
                   s.tolerance, chosen_name.c_str(), c.estimated_error, real,
                   ok ? (best == chosen_name ? "" : "  (not the cheapest)") : "  NOT BOUNDED");
    } catch (const Error& e) {
      ++failed;
      std::fprintf(stderr, "%3d %s: failed: %s\n", i, s.kind.c_str(), e.what());
      csv << i << ',' << s.kind << ',' << s.layer.nu << ",,,,,failed,,,0,,0\n";
    }
  }
  std::printf("# Model \"auto\" on %d random scenes (tools/auto_validation.cpp)\n\n", count);
  std::printf("| | scenes |\n|---|---|\n");
  std::printf("| estimate bounds the real error (pull-off force, zero-load radius vs a finer exact layer) | %d / %d |\n",
              bounded, count);
  std::printf("| the choice is the cheapest model really within tolerance | %d / %d (%.1f %%) |\n", cheapest, count,
              100.0 * cheapest / count);
  std::printf("| scenes that failed to solve | %d |\n", failed);
  std::printf("| largest real error / estimate | %.3g |\n\n", worst_ratio);
  std::printf("Choices:");
  for (const auto& [m, n] : chosen) std::printf(" %s %d;", m.c_str(), n);
  std::printf("\n\nPer scene: [auto_validation.csv](auto_validation.csv).\n");
  return bounded == count - failed && failed == 0 ? 0 : 1;
}
