// What Maugis-Dugdale and DMT states cost on a layer (adhesion/dugdale_solver): one state,
// the same with its two-grid error estimate, one from the medium's Dugdale table (built before
// the rows, its cost printed apart), and a 40-radius curve, against the exact layer's
// non-adhesive state at the same a/h; the half-space state for scale.
//
// How the data is made: a paraboloid R = 100 h on a bonded incompressible layer (E* = 1 MPa,
// h = 1 um, w = 50 mJ/m^2, sigma0 for Maugis' lambda = 1 with the layer's E*), the default
// discretisation (16 nodes on 3h panels), the kernel built beforehand, the median of 5 runs.
//
// Run: LAYERJKR_CACHE=off build/bin/adhesion_layer_cost   (~30 s; prints a markdown table)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "adhesion/dugdale_solver.hpp"
#include "layerjkr/exact_layer.hpp"
#include "median_time.hpp"

using namespace layerjkr;
using layerjkr::bench::median_seconds;

int main() {
  const double h = 1e-6, R = 100 * h, E_star = 1e6, w = 0.05, pi = std::acos(-1.0);
  const double K = 4.0 * E_star / 3.0, sigma0 = 0.5 * std::cbrt(pi * w * K * K / R);  // lambda = 1
  const ElasticLayer layer{0.75 * E_star, 0.5, h, Base::bonded};
  ExactLayerOptions plain;
  plain.tabulate_power_laws = false;
  const auto kernel = std::make_shared<const ExactLayerKernel>(layer, plain);
  const auto profile = make_paraboloid(R);
  const detail::DugdaleSolver md(profile, kernel);
  const detail::DugdaleSolver half(profile, E_star);
  const auto tabulated_kernel = std::make_shared<const ExactLayerKernel>(layer);
  const detail::DugdaleSolver table(profile, tabulated_kernel, true);
  const auto t0 = std::chrono::steady_clock::now();
  for (double a_over_h : {0.0, 1.0, 4.0, 20.0}) table.maugis_dugdale(a_over_h * h, w, sigma0);
  std::printf("The medium's Dugdale table, the pieces these rows reach: %.2f s once; measured error %.2g\n\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), table.table_error());
  std::printf("| a/h | exact-layer state | MD state | MD + estimate | DMT state | MD from the table | half-space MD |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (double a_over_h : {0.0, 1.0, 4.0, 20.0}) {
    const double a = a_over_h * h;
    const double t_h = a > 0 ? median_seconds([&] { kernel->state(*profile, a); }, 5) : 0.0;
    const double t_md = median_seconds([&] { md.maugis_dugdale(a, w, sigma0); }, 5);
    const double t_est = median_seconds([&] { md.maugis_dugdale_estimate(a, w, sigma0); }, 5);
    const double t_dmt = median_seconds([&] { md.dmt(a, w, sigma0); }, 5);
    const double t_table = median_seconds([&] { table.maugis_dugdale(a, w, sigma0); }, 5);
    const double t_half = median_seconds([&] { half.maugis_dugdale(a, w, sigma0); }, 5);
    std::printf("| %g | %.3g ms | %.3g ms | %.3g ms | %.3g ms | %.3g us | %.3g us |\n", a_over_h, 1e3 * t_h,
                1e3 * t_md, 1e3 * t_est, 1e3 * t_dmt, 1e6 * t_table, 1e6 * t_half);
  }
  const double t_curve = median_seconds(
      [&] {
        for (int j = 1; j <= 40; ++j) md.maugis_dugdale(10.0 * h * j / 40, w, sigma0);
      },
      3);
  std::printf("\n40-radius Maugis-Dugdale curve, a/h = 0.25..10: %.3g s (%.3g ms a state)\n", t_curve,
              1e3 * t_curve / 40);
  return 0;
}
