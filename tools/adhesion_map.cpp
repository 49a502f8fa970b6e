// The adhesion map of docs/models.md: where JKR is within 1 % and 5 % of Maugis-Dugdale on an
// elastic layer, against Maugis' lambda of the contact (adhesion_check.hpp) and the JKR pull-off
// radius over the layer's thickness, a_c/h; and how well the check's half-space estimate
// predicts the error it measures here.
//
// A paraboloid R on a bonded layer (E = 1 MPa, h = 1 um, nu as given) with w = 0.05 J/m^2: R sets
// a_c/h, and sigma0 (lambda is linear in it) sets lambda. Each cell solves both pull-offs on the
// exact layer: JKR by the transform, Maugis-Dugdale by the Dugdale solver. Prints a table.
//
// Run: build/bin/adhesion_map [nu]   (about a minute)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "layerjkr/layerjkr.hpp"

namespace {

using namespace layerjkr;

struct Cell {
  double a_over_h = 0.0, lambda = 0.0, error = 0.0, estimate = 0.0;
};

Cell measure(double R, double lambda, double nu) {
  const double E = 1e6, h = 1e-6, w = 0.05;
  ModelSpec spec;
  spec.kind = ModelKind::exact;
  spec.layer = ElasticLayer{E, nu, h, Base::bonded};
  const ContactModelPtr model = make_contact_model(make_paraboloid(R), spec);
  const AdhesiveSolution jkr(model, w);
  const CriticalPoint jkr_pull_off = *jkr.pull_off();
  // lambda is linear in sigma0: scale a trial stress to the target.
  const double sigma0 = lambda / contact_lambda(model->state(jkr_pull_off.a), w, 1.0);
  AdhesionSpec md;
  md.model = AdhesionModel::maugis_dugdale;
  md.sigma0 = sigma0;
  const AdhesiveSolution dugdale(make_adhesive_law(model, spec, w, md));
  Cell c;
  c.a_over_h = jkr_pull_off.a / h;
  c.lambda = lambda;
  c.error = jkr_pull_off.P / dugdale.pull_off()->P - 1.0;  // signed: > 0 where JKR pulls harder
  c.estimate = check_adhesion(jkr, jkr, md)->pull_off_error;  // no medium: the half-space estimate
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  const double nu = argc > 1 ? std::atof(argv[1]) : 0.45;
  const double radii[] = {1e-8, 1e-7, 1e-6, 1e-5, 1e-4};
  const double lambdas[] = {0.1, 0.3, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 30.0};
  std::printf("JKR pull-off error against Maugis-Dugdale on a bonded layer, nu = %g: measured P_JKR/P_MD - 1 in %% (the check's half-space estimate of |.|, %%)\n", nu);
  std::printf("%8s", "lambda");
  const auto start = std::chrono::steady_clock::now();
  bool header = false;
  for (double lambda : lambdas) {
    Cell row[5];
    for (int i = 0; i < 5; ++i) row[i] = measure(radii[i], lambda, nu);
    if (!header) {
      for (const Cell& c : row) std::printf("   a_c/h = %-9.3g", c.a_over_h);
      std::printf("\n");
      header = true;
    }
    std::printf("%8.3g", lambda);
    for (const Cell& c : row) std::printf("   %+6.2f (%5.2f)  ", 100.0 * c.error, 100.0 * c.estimate);
    std::printf("\n");
  }
  std::printf("(%.0f s)\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}
