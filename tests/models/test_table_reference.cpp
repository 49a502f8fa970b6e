// The error estimate of a scene with a measured table indenter costs a bounded number of
// solves: the exact-layer reference sees the table resampled (src/judge/model_error.cpp).
// Before, a 10 000-point table made summary run for minutes (more than 300 s measured).
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

namespace {

// The hydrogel two-term scene with its paraboloid (R = 10 um) given as a table of n points.
Scene table_scene(int n) {
  std::string r = "[", z = "[";
  for (int i = 0; i < n; ++i) {
    const double x = 5e-6 * i / (n - 1);
    r += (i ? "," : "") + format_double(x);
    z += (i ? "," : "") + format_double(x * x / 2e-5);
  }
  return parse_scene(R"({"indenter": {"shape": "table", "r": )" + r + R"(], "z": )" + z +
                     R"(]}, "medium": {"type": "layer", "E": 5e4, "nu": 0.3, "h": 2e-7, "base": "bonded"},
                        "model": "two_term", "w": 0.001})");
}

const Scene& paraboloid() {
  static const Scene s = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-5},
      "medium": {"type": "layer", "E": 5e4, "nu": 0.3, "h": 2e-7, "base": "bonded"}, "model": "two_term", "w": 0.001})");
  return s;
}

}  // namespace

TEST_CASE("a 10 000-point table indenter: summary and curve with the paraboloid's error estimate", "[models][table]") {
  const Scene table = table_scene(10000);
  const SummaryAnswer t = solve_summary(table);
  const SummaryAnswer p = solve_summary(paraboloid());
  REQUIRE(t.contact.pull_off);
  CHECK(t.contact.pull_off->P == Approx(p.contact.pull_off->P).epsilon(1e-8));
  CHECK(t.error.reference == "exact");
  CHECK(t.error.pull_off_force == Approx(p.error.pull_off_force).epsilon(1e-4));
  CHECK(t.error.zero_load_radius == Approx(p.error.zero_load_radius).epsilon(1e-4));
  const std::vector<double> radii{1e-7, 5e-7, 1e-6, 2e-6};
  const CurveAnswer ct = solve_curve(table, radii), cp = solve_curve(paraboloid(), radii);
  for (std::size_t i = 0; i < radii.size(); ++i) {
    INFO("a = " << radii[i]);
    CHECK(ct.error_estimate[i] == Approx(cp.error_estimate[i]).epsilon(1e-3));
  }
}
