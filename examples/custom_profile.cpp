// What this teaches: the library API end to end for an indenter that has no closed
// form - a blunted cone given as a C++ generic lambda, differentiated automatically -
// on a full Pasternak foundation: model -> JKR solution -> pull-off and lookups.
//
// It also shows the one rule for callables: write f without cancellation. The tip
// below is cot(alpha) (sqrt(r^2 + b^2) - b), but coded as cot r^2 / (sqrt(r^2 + b^2) + b);
// the naive form loses half its digits for r << b and the quadratures refuse it.
//
// How the data is made: nothing is measured. The tip is f(r) = cot(alpha) *
// (sqrt(r^2 + b^2) - b), a cone of semi-angle 70 deg rounded to radius ~b = 200 nm at
// its apex; the foundation constants are illustrative (K = 1e14 N/m^3, G = 0.5 N/m,
// a soft 100 nm hydrogel film), w = 0.02 J/m^2.
//
// Run: build/bin/custom_profile
#include <cmath>
#include <cstdio>

#include "layerjkr/callable_profile.hpp"
#include "layerjkr/layerjkr.hpp"

int main() {
  const double cot = 1.0 / std::tan(70.0 * M_PI / 180.0), b = 200e-9;
  const auto tip = layerjkr::make_callable_profile(
      [cot, b](auto r) {
        using std::sqrt;
        return cot * r * r / (sqrt(r * r + b * b) + b);
      },
      /*length_scale=*/b, /*max_radius=*/INFINITY, "blunted cone");
  const auto model = layerjkr::make_full_foundation(tip, 1e14, 0.5);
  const layerjkr::JkrSolution jkr(model, 0.02);

  const layerjkr::ContactSummary summary = layerjkr::summarize(jkr);
  std::printf("%s\n", summary.brief_report().c_str());

  std::printf("%12s %14s %14s\n", "a [nm]", "P [nN]", "delta [nm]");
  for (double a : {50e-9, 100e-9, 200e-9, 400e-9, 800e-9}) {
    const layerjkr::AdhesiveState s = jkr.at(a);
    std::printf("%12.1f %14.5f %14.5f\n", a * 1e9, s.P * 1e9, s.delta * 1e9);
  }
  const double P = 50e-9;
  std::printf("\nat P = 50 nN: a = %.5f nm (stable branch)\n", jkr.contact_radius_at_force(P) * 1e9);
  return 0;
}
