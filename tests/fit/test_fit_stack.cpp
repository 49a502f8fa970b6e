// Fitting a stack of layers (issue 24): the tabulated exact stack scaled by E, i.e. every
// modulus of the stack scaled together with their ratios fixed; E reported is the top layer's.
#include <catch2/catch.hpp>

#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/simulate.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

TEST_CASE("a stack's exact model recovers its noiseless curve, scaling every modulus together", "[fit][stack]") {
  // 1 MPa, 50 um coating on a 20 MPa, 100 um layer on glass (bonded), a 1 mm paraboloid
  const Scene truth = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layers", "layers": [{"E": 1e6, "nu": 0.45, "h": 5e-5}, {"E": 2e7, "nu": 0.3, "h": 1e-4}],
                 "base": "bonded"}, "model": "exact", "w": 0.05})");
  SimulationOptions so;
  so.points_per_branch = 150;
  so.delta0 = 5e-7;
  so.max_indentation = 4e-6;
  const CurveData data = simulate_curve(truth, so);
  Scene guess = truth;  // every modulus 20x too high (ratios kept), no adhesion
  guess.w = 0.0;
  for (StackLayer& l : guess.medium.stack.layers) l.E *= 20.0;
  guess.medium.E *= 20.0;
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::w, FitParameter::delta0};
  o.branch = Branch::all;
  const FitSummary s = fit(data, guess, o);
  INFO(s.brief_report());
  CHECK(s.converged);
  CHECK(rel_err(s[FitParameter::E].value, 1e6) < 1e-5);  // the top layer's E
  CHECK(rel_err(s[FitParameter::w].value, 0.05) < 1e-4);
  CHECK(std::abs(s[FitParameter::delta0].value - 5e-7) < 1e-4 * so.max_indentation);
}
