// The exact layer's per-(nu, base, d) power-law tables against direct solves: the tabulated
// model must be indistinguishable from solving each radius (oracle: ExactLayerKernel::state).
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>
#include <vector>

#include "layerjkr/contact.hpp"
#include "layerjkr/exact_layer.hpp"
#include "models/exact_power_law_table.hpp"
#include "support/test_support.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;
using test::rel_err;

namespace {
double worst_rel_err(const NonAdhesiveState& s, const NonAdhesiveState& r) {
  return std::max({rel_err(s.P_H, r.P_H), rel_err(s.delta_H, r.delta_H), rel_err(s.S, r.S),
                   rel_err(s.dS_da, r.dS_da)});
}
}  // namespace

TEST_CASE("tabulated power laws equal direct solves from a/h = 3e-7 to 60", "[exact][table]") {
  struct Case {
    ElasticLayer layer;
    ProfilePtr profile;
  };
  const Case cases[] = {{{2.0, 0.49, 1.5, Base::bonded}, make_paraboloid(300.0)},
                        {{2.0, 0.5, 1.5, Base::bonded}, make_cone(1.2)},
                        {{2.0, 0.3, 1.5, Base::frictionless}, make_power_law(0.1, 1.5)},
                        {{2.0, 0.0, 1.5, Base::bonded}, make_power_law(0.02, 3.0)}};
  for (const Case& c : cases) {
    ExactLayerOptions o;
    const auto model = make_exact_layer(c.profile, c.layer, o);
    const ExactLayerKernel direct(c.layer, o);
    double worst = 0.0;
    for (double rho = 3e-7; rho < 60.0; rho *= 1.37) {
      const double a = rho * c.layer.h;
      worst = std::max(worst, worst_rel_err(model->state(a), direct.state(*c.profile, a)));
    }
    INFO(c.profile->describe() << " nu = " << c.layer.nu);
    CHECK(worst < 1e-9);
  }
}

TEST_CASE("power-law tables: the first query of a piece is safe from several threads", "[exact][table]") {
  ExactLayerOptions o;
  o.points_per_panel = 12;  // a discretisation no other test uses: the table is new here
  const auto table = detail::shared_power_law_table(0.45, Base::bonded, 2.0, o);
  std::vector<detail::ExactMoments> got(4);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i) threads.emplace_back([&, i] { got[i] = table->at(3.3); });
  for (std::thread& t : threads) t.join();
  for (const detail::ExactMoments& m : got) {
    CHECK(m.int0 == got[0].int0);
    CHECK(m.endf == got[0].endf);
  }
  CHECK(detail::shared_power_law_table(0.45, Base::bonded, 2.0, o) == table);
  CHECK_THROWS_WITH(table->at(1e-7), Catch::Contains("a/h = 1e-07") && Catch::Contains("valid range"));
}

TEST_CASE("profiles say when they are power laws", "[exact][table]") {
  CHECK(make_paraboloid(2.0)->power_law_form()->B == 0.25);
  CHECK(make_paraboloid(2.0)->power_law_form()->d == 2.0);
  CHECK(make_cone(0.5)->power_law_form()->B == Approx(1.0 / std::tan(0.5)).epsilon(1e-15));
  CHECK(make_power_law(3.0, 1.5)->power_law_form()->d == 1.5);
  CHECK_FALSE(make_sphere(1.0)->power_law_form());
  CHECK_FALSE(make_table_profile({0.0, 1.0, 2.0}, {0.0, 0.5, 2.0})->power_law_form());
}

TEST_CASE("tabulated exact layer: pull-off equals the fine dense solver's to 1e-8", "[exact][table]") {
  // Oracle: the fine setting (h/4 panels, 12 nodes, dense, every radius solved) that was the
  // reference before the tables; the accuracy target is 1e-8 for the pull-off.
  ExactLayerOptions fine;
  fine.points_per_panel = 12;
  fine.panel_width = 0.25;
  fine.max_a_over_h = 60.0;
  fine.dense_max_unknowns = 100000;
  fine.tabulate_power_laws = false;
  const auto p = make_paraboloid(200.0);
  for (double nu : {0.3, 0.49, 0.5}) {
    for (Base base : {Base::bonded, Base::frictionless}) {
      const ElasticLayer layer{1.0, nu, 1.0, base};
      const JkrSolution fast(make_exact_layer(p, layer), 0.05), reference(make_exact_layer(p, layer, fine), 0.05);
      const auto a = fast.pull_off(), b = reference.pull_off();
      REQUIRE(a);
      REQUIRE(b);
      INFO("nu = " << nu << " bonded = " << (base == Base::bonded) << " pull-off a/h = " << b->a);
      CHECK(rel_err(a->P, b->P) < 1e-8);
      CHECK(rel_err(a->delta, b->delta) < 1e-8);
    }
  }
}
