// What this teaches: what an asymptotic model costs you in a fit. Curves made with the
// exact elastic layer are fitted with the Winkler (leading), two-term, edge-corrected and
// exact models; the bias in E and w is the error a user makes by choosing the cheaper
// model, as a function of a_max/h (contact radius at the deepest point over thickness).
//
// How the data is made: a paraboloid (R = 1 mm) on a bonded layer (E = 1 MPa, h = 10 um,
// nu = 0.3 and 0.45) with w = 0.05 J/m^2. The retract branch is sampled directly in a -
// 80 radii from a_max down to the exact model's pull-off radius, each state from
// make_exact_layer and jkr_transform, no root finding - plus 40 free samples after
// pull-off. No noise: every residual is model error. Fits free E, w and delta0.
//
// Run: build/bin/fit_bias_vs_exact [docs/data]   (about a minute; writes fit_bias_vs_exact.csv)
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include "layerjkr/layerjkr.hpp"

int main(int argc, char** argv) {
  using namespace layerjkr;
  const std::string dir = argc > 1 ? argv[1] : ".";
  std::ofstream csv(dir + "/fit_bias_vs_exact.csv");
  csv << "nu,a_max_over_h,model,E_bias,w_bias,rms_over_pulloff\n";
  std::printf("| nu | a_max/h | model | E bias | w bias | rms / pull-off |\n|---|---|---|---|---|---|\n");
  const double E = 1e6, h = 1e-5, w = 0.05, R = 1e-3;
  for (double nu : {0.3, 0.45}) {
    const ElasticLayer layer{E, nu, h, Base::bonded};
    Scene scene;
    scene.profile = make_paraboloid(R);
    scene.medium.type = MediumType::layer;
    scene.medium.E = E;
    scene.medium.nu = nu;
    scene.medium.h = h;
    scene.w = w;
    const ContactModelPtr exact = make_exact_layer(scene.profile, layer);
    const JkrSolution jkr(exact, w);
    const CriticalPoint po = *jkr.pull_off();
    for (double ratio : {2.0, 5.0, 10.0, 20.0, 40.0}) {
      const double a_max = ratio * h;
      if (a_max <= 1.2 * po.a) continue;
      CurveData c;
      for (int i = 0; i < 80; ++i) {
        const double a = a_max - (a_max - po.a) * i / 79.0;
        const AdhesiveState s = jkr_transform(exact->state(a), w);
        c.delta.push_back(s.delta);
        c.P.push_back(s.P);
        c.segment.push_back(1);
      }
      const double span = c.delta.front() - po.delta;
      for (int i = 1; i <= 40; ++i) {
        c.delta.push_back(po.delta - span * i / 80.0);
        c.P.push_back(0.0);
        c.segment.push_back(1);
      }
      for (const SceneModel model : {SceneModel::leading, SceneModel::two_term,
                                     SceneModel::edge_corrected, SceneModel::exact}) {
        Scene s = scene;
        s.model = model;
        s.medium.E = 2e5;  // the start must not matter
        s.w = 0.0;
        FitOptions o;
        o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
        o.branch = Branch::retract;
        try {
          const FitSummary f = fit(c, s, o);
          const double eb = f[FitParameter::E].value / E - 1.0, wb = f[FitParameter::w].value / w - 1.0;
          const double rr = f.rms_residual / std::abs(po.P);
          std::printf("| %.2f | %.0f | %s | %+.2f %% | %+.2f %% | %.1e |\n", nu, ratio, to_string(model), 100 * eb,
                      100 * wb, rr);
          csv << nu << "," << ratio << "," << to_string(model) << "," << eb << "," << wb << "," << rr << "\n";
        } catch (const Error& e) {
          std::printf("| %.2f | %.0f | %s | failed: %s | | |\n", nu, ratio, to_string(model), e.what());
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
