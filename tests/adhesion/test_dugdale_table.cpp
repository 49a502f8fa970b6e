// The Dugdale tables (adhesion/dugdale_table): the tabulated linear parts against direct solves
// at points the table was not built on, each within its piece's measured error; Maugis-Dugdale
// and DMT states from the table against the direct solver, with the estimate bounding the
// difference; the half-space limit. Oracle: DugdaleSolver::parts and the untabulated solver.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "adhesion/dugdale_solver.hpp"
#include "adhesion/dugdale_table.hpp"
#include "layerjkr/exact_layer.hpp"
#include "support/stack_media.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
using detail::DugdaleParts;
using detail::DugdaleSolver;
using detail::DugdaleTable;

namespace {

ExactLayerOptions options() {
  ExactLayerOptions o;
  o.max_a_over_h = 100.0;
  return o;
}

// Relative to the larger of the part and its half-space size, as the table's error is.
double part_error(double table, double direct, double half_space) {
  return std::abs(table - direct) / std::max(std::abs(half_space), std::abs(direct));
}

void check_parts(const LayeredMedium& medium, double d, double c_lo, double c_hi, int samples) {
  const auto table = detail::shared_dugdale_table(medium, d, options());
  LayeredMedium unit = medium;  // the table's units: E1 = h1 = 1
  const double E1 = medium.layers[0].E, h1 = medium.layers[0].h;
  for (StackLayer& l : unit.layers) {
    l.E /= E1;
    l.h /= h1;
  }
  if (unit.substrate) unit.substrate->E /= E1;
  const DugdaleSolver direct(make_power_law(1.0, d), std::make_shared<ExactLayerKernel>(unit, options()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < samples; ++i) {
    const double c = c_lo * std::pow(c_hi / c_lo, u(rng)), a = c * u(rng);
    const DugdaleTable::Parts t = table->at(a, c), hs = DugdaleTable::half_space(a, c, d);
    const DugdaleParts p = direct.parts(a, c, options().points_per_panel);
    INFO("d = " << d << ", a/h = " << a << ", c/h = " << c << ", measured error " << t.error);
    const double e = std::max({part_error(t.D, p.D, hs.D), part_error(t.P, p.P, hs.P), part_error(t.G, p.G, hs.G),
                               part_error(t.F, p.F, hs.F)});
    CHECK(e < 3.0 * t.error + 1e-12);  // the piece's own statement, within a factor of its sampling
    CHECK(e < 1e-6);
  }
}

}  // namespace

TEST_CASE("Dugdale table: the parts between its points agree with direct solves within the measured error",
          "[dugdale][table]") {
  check_parts(test::stack({{1.0, 0.3, 1.0}}), 2.0, 0.05, 20.0, 24);
  check_parts(test::stack({{1.0, 0.5, 1.0}}, Base::frictionless), 1.0, 0.3, 5.0, 8);
  check_parts(test::on_half_space({{1.0, 0.45, 1.0}, {20.0, 0.3, 0.5}}, 0.5, 0.49), 2.0, 0.3, 5.0, 8);
}

TEST_CASE("Dugdale table: Maugis-Dugdale and DMT states agree with the direct solver, the estimate bounds the gap",
          "[dugdale][table]") {
  // The film: a 20 nm paraboloid on a 10 nm bonded film (E = 3 GPa, nu = 0.3).
  const ElasticLayer film{3e9, 0.3, 1e-8, Base::bonded};
  ExactLayerOptions o;
  const auto kernel = std::make_shared<ExactLayerKernel>(film, o);
  const DugdaleSolver tabulated(make_paraboloid(2e-8), kernel, true), direct(make_paraboloid(2e-8), kernel);
  REQUIRE(tabulated.tabulated());
  for (double sigma0 : {50e6, 170e6, 1e9})
    for (double a : {0.0, 2e-9, 8e-9, 2e-8}) {
      const detail::DugdaleEstimate t = tabulated.maugis_dugdale_estimate(a, 0.05, sigma0);
      const AdhesiveState d = direct.maugis_dugdale(a, 0.05, sigma0);
      INFO("sigma0 = " << sigma0 << ", a = " << a << ": P " << t.state.P << " vs " << d.P << " (estimate "
                       << t.P_error << "), delta " << t.state.delta << " vs " << d.delta << ", c " << t.state.c
                       << " vs " << d.c);
      CHECK(std::abs(t.state.P - d.P) <= t.P_error + 1e-12 * std::abs(d.P));
      CHECK(std::abs(t.state.delta - d.delta) <= t.delta_error + 1e-12 * std::abs(d.delta));
      CHECK(std::abs(t.state.P - d.P) < 1e-5 * std::abs(d.P));
      CHECK(std::abs(t.state.delta - d.delta) < 1e-5 * (std::abs(d.delta) + 1e-10));
      CHECK(std::abs(t.state.c - d.c) < 1e-5 * d.c);
      const detail::DugdaleEstimate td = tabulated.dmt_estimate(a, 0.05, sigma0);
      const AdhesiveState dd = direct.dmt(a, 0.05, sigma0);
      CHECK(std::abs(td.state.P - dd.P) <= td.P_error + 1e-12 * std::abs(dd.P));
      CHECK(std::abs(td.state.P - dd.P) < 1e-5 * std::abs(dd.P));
      CHECK(std::abs(td.state.c - dd.c) < 1e-5 * dd.c);
    }
  CHECK(tabulated.table_error() > 0.0);
  CHECK(tabulated.table_error() < 1e-6);
}

TEST_CASE("Dugdale table: the ratios tend to the half-space's as c/h goes to 0", "[dugdale][table]") {
  const auto table = detail::shared_dugdale_table(test::stack({{1.0, 0.4, 1.0}}), 2.0, options());
  for (double c : {1e-6, 1e-5, 1e-4}) {
    const DugdaleTable::Parts t = table->at(0.5 * c, c), hs = DugdaleTable::half_space(0.5 * c, c, 2.0);
    INFO("c/h = " << c);
    CHECK(std::abs(t.D / hs.D - 1.0) < 20.0 * c);  // O(c/h): the layer's rigid shift
    CHECK(std::abs(t.P / hs.P - 1.0) < 20.0 * c);
    CHECK(std::abs(t.G / hs.G - 1.0) < 20.0 * c);
    CHECK(std::abs(t.F / hs.F - 1.0) < 20.0 * c);
  }
  CHECK_THROWS_AS(table->at(0.1, 1e3), DomainError);
  CHECK_THROWS_AS(table->at(2.0, 1.0), DomainError);
}
