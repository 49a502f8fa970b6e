// The exact layer solver: published flat-punch factors, refinement, and both limits.
#include <catch2/catch.hpp>

#include <cmath>

#include <boost/math/differentiation/finite_difference.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>

#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;
using test::rel_err;

namespace {
ExactLayerOptions fine_options(double max_a_over_h) {
  ExactLayerOptions o;
  o.max_a_over_h = max_a_over_h;
  o.points_per_panel = 12;
  o.panel_width = 0.25;
  return o;
}
ExactLayerOptions range(double max_a_over_h) {
  ExactLayerOptions o;
  o.max_a_over_h = max_a_over_h;
  return o;
}
}  // namespace

TEST_CASE("flat-punch factors match the published table (theory.md s.4)", "[exact]") {
  const ExactLayerKernel k03({1.0, 0.3, 1.0, Base::bonded}, range(6)),
      k05({1.0, 0.5, 1.0, Base::bonded}, range(6));
  const double a_over_h[] = {0.2, 1.0, 5.0};
  const double nu03[] = {1.2066, 2.4835, 10.0998}, nu05[] = {1.2806, 3.6187, 50.1397};
  for (int i = 0; i < 3; ++i) {
    INFO("a/h=" << a_over_h[i]);
    CHECK(std::abs(k03.flat_punch_factor(a_over_h[i]) - nu03[i]) < 6e-5);
    CHECK(std::abs(k05.flat_punch_factor(a_over_h[i]) - nu05[i]) < 6e-5);
  }
}

TEST_CASE("exact layer converges under refinement to better than 1e-6", "[exact]") {
  const auto p = make_paraboloid(100.0);
  for (double nu : {0.0, 0.3, 0.49, 0.5}) {
    for (Base base : {Base::bonded, Base::frictionless}) {
      const ElasticLayer layer{2.0, nu, 1.0, base};
      const ExactLayerKernel normal(layer, range(20)), fine(layer, fine_options(20));
      for (double a : {0.01, 1.0, 20.0}) {
        const ExactLayerState s = normal.solve(*p, a), r = fine.solve(*p, a);
        INFO("nu=" << nu << " bonded=" << (base == Base::bonded) << " a/h=" << a);
        CHECK(rel_err(s.state.P_H, r.state.P_H) < 1e-7);
        CHECK(rel_err(s.state.delta_H, r.state.delta_H) < 1e-7);
        CHECK(s.P_H_error < 1e-6);
        CHECK(s.delta_H_error < 1e-6);
      }
    }
  }
}

TEST_CASE("exact layer stays within 1e-6 at a/h = 100 against a finer setting", "[exact]") {
  const auto p = make_paraboloid(1000.0);
  for (double nu : {0.3, 0.5}) {
    const ElasticLayer layer{1.0, nu, 1.0, Base::bonded};
    ExactLayerOptions normal = range(100), finer = range(100);
    normal.estimate_error = finer.estimate_error = false;
    finer.points_per_panel = 10;
    finer.panel_width = 0.4;
    const NonAdhesiveState a = ExactLayerKernel(layer, normal).solve(*p, 100.0).state;
    const NonAdhesiveState b = ExactLayerKernel(layer, finer).solve(*p, 100.0).state;
    INFO("nu=" << nu);
    CHECK(rel_err(a.P_H, b.P_H) < 1e-6);
    CHECK(rel_err(a.delta_H, b.delta_H) < 1e-6);
  }
}

TEST_CASE("exact layer sweep: one factorisation gives every panel-boundary radius", "[exact][sweep]") {
  // Oracle: an independent solve per radius on the same panels (the sweep's radius a_max j/n
  // uses the leading j panels of its grid, so each single solve must see exactly those).
  const auto sphere = make_sphere(40.0);  // not a paraboloid: the profile column is general
  for (double nu : {0.3, 0.5}) {
    for (Base base : {Base::bonded, Base::frictionless}) {
      const ElasticLayer layer{3.0, nu, 1.0, base};
      ExactLayerOptions o = range(12);
      o.estimate_error = false;
      o.panel_width = 0.5;
      o.min_panels = 2;
      const ExactLayerKernel k(layer, o);
      const int count = 6;
      const std::vector<NonAdhesiveState> swept = k.sweep(*sphere, 12.0, count);  // 4 panels per step
      REQUIRE(swept.size() == std::size_t(count));
      for (int j = 1; j <= count; ++j) {
        const NonAdhesiveState single = k.solve(*sphere, 2.0 * j).state;
        INFO("nu=" << nu << " bonded=" << (base == Base::bonded) << " a=" << 2.0 * j);
        CHECK(swept[j - 1].a == Approx(2.0 * j));
        CHECK(rel_err(swept[j - 1].P_H, single.P_H) < 1e-11);
        CHECK(rel_err(swept[j - 1].delta_H, single.delta_H) < 1e-11);
        CHECK(rel_err(swept[j - 1].S, single.S) < 1e-11);
        CHECK(rel_err(swept[j - 1].dS_da, single.dS_da) < 1e-11);
      }
    }
  }
  const ExactLayerKernel k({1.0, 0.3, 1.0, Base::bonded}, range(5));
  CHECK_THROWS_WITH(k.sweep(*sphere, 4.0, 0), Catch::Contains("count = 0"));
  CHECK_THROWS_WITH(k.sweep(*sphere, 6.0, 3), Catch::Contains("a/h = 6"));
}

TEST_CASE("exact model: an evenly spaced curve comes from the sweep, others radius by radius", "[exact][sweep]") {
  const auto p = make_paraboloid(30.0);
  ExactLayerOptions o = range(20);
  o.estimate_error = false;
  const auto model = make_exact_layer(p, {1.0, 0.45, 1.0, Base::bonded}, o);
  std::vector<double> even, uneven;
  for (int j = 1; j <= 40; ++j) even.push_back(20.0 * j / 40);
  for (int j = 1; j <= 7; ++j) uneven.push_back(0.3 * j * j);
  const std::vector<NonAdhesiveState> swept = model->states(even), single = model->states(uneven);
  for (std::size_t j = 0; j < even.size(); ++j) {  // different panels: both converged to 1e-8
    const NonAdhesiveState r = model->state(even[j]);
    INFO("a/h=" << even[j]);
    CHECK(swept[j].a == even[j]);
    CHECK(rel_err(swept[j].P_H, r.P_H) < 1e-8);
    CHECK(rel_err(swept[j].delta_H, r.delta_H) < 1e-8);
    CHECK(rel_err(swept[j].dS_da, r.dS_da) < 1e-8);
  }
  for (std::size_t j = 0; j < uneven.size(); ++j) CHECK(single[j].P_H == model->state(uneven[j]).P_H);
  // The curve uses the same path.
  const JkrSolution jkr(model, 1e-3);
  const std::vector<AdhesiveState> c = jkr.curve(even);
  CHECK(c.back().P == jkr_transform(swept.back(), 1e-3).P);
}

TEST_CASE("exact layer: thick limit is the half-space, with an O(a/h) shift", "[exact]") {
  const double R = 50.0, nu = 0.3, Es = 1.0 / (1 - nu * nu);
  const auto p = make_paraboloid(R);
  const ExactLayerKernel k({1.0, nu, 1.0, Base::bonded}, range(1));
  double previous = 0.0;
  for (double a : {1e-2, 1e-3, 1e-4}) {
    const NonAdhesiveState s = k.solve(*p, a).state;
    const double e_delta = rel_err(s.delta_H, a * a / R);
    INFO("a/h=" << a << " delta error " << e_delta);
    CHECK(rel_err(s.P_H, 4 * Es * a * a * a / (3 * R)) < 2 * a * a);
    if (previous > 0.0) CHECK(rel_err(previous / e_delta, 10.0) < 0.05);  // linear in a/h
    previous = e_delta;
  }
  // Sneddon flat punch, S = 2 E* a, at a/h -> 0.
  CHECK(rel_err(k.flat_punch_factor(1e-4), 1.0) < 2e-4);
}

TEST_CASE("exact layer: thin limit approaches Winkler as theory.md s.6 reports", "[exact]") {
  const ThinLayerConstants c = thin_layer_constants({1.0, 0.3, 1.0, Base::bonded});
  const auto p = make_paraboloid(1000.0);
  const ExactLayerKernel k({1.0, 0.3, 1.0, Base::bonded}, range(20));
  const double a_over_h[] = {2.0, 5.0, 8.0, 20.0}, ratio[] = {1.30, 1.10, 1.06, 1.025};
  for (int i = 0; i < 4; ++i) {
    const double exact = k.solve(*p, a_over_h[i]).state.P_H;
    const double winkler = make_winkler(p, c.K)->state(a_over_h[i]).P_H;
    INFO("a/h=" << a_over_h[i]);
    CHECK(std::abs(exact / winkler - ratio[i]) < 0.005);
  }
}

TEST_CASE("exact layer satisfies S = dP_H/d delta_H and S' = 2 E* phi0(a)^2", "[exact]") {
  for (double nu : {0.3, 0.5}) {
    const auto model = make_exact_layer(make_sphere(30.0), {1.0, nu, 1.0, Base::bonded}, range(10));
    for (double a : {0.3, 2.0, 7.0}) {
      auto along = [&](auto field) {
        auto g = [&](double x) { return field(model->state(std::exp(x))); };
        return boost::math::differentiation::finite_difference_derivative<decltype(g), double, 6>(
                   g, std::log(a)) / a;
      };
      const NonAdhesiveState s = model->state(a);
      const double dP = along([](const NonAdhesiveState& h) { return h.P_H; });
      const double dd = along([](const NonAdhesiveState& h) { return h.delta_H; });
      const double dS = along([](const NonAdhesiveState& h) { return h.S; });
      INFO("nu=" << nu << " a/h=" << a);
      CHECK(rel_err(dP / dd, s.S) < 1e-6);
      CHECK(rel_err(dS, s.dS_da) < 1e-6);
    }
  }
}

TEST_CASE("exact layer JKR: thick layers give the classical -3/2 pi w R", "[exact][contact]") {
  // w R^2 / (E* h^3) = 1e-7: the contact is far smaller than the layer.
  const double R = 1e-3, w = 1e-4, h = 1e-2;
  const JkrSolution jkr(make_exact_layer(make_paraboloid(R), {1e5, 0.4, h, Base::bonded}, range(1)), w);
  const auto po = jkr.pull_off();
  REQUIRE(po);
  CHECK(rel_err(po->P, -1.5 * M_PI * w * R) < 1e-3);
  CHECK(po->P < -1.5 * M_PI * w * R);  // a finite layer pulls off slightly harder
}

TEST_CASE("exact layer rejects invalid input", "[exact][errors]") {
  const auto p = make_paraboloid(1.0);
  CHECK_THROWS_WITH(ExactLayerKernel({1.0, 0.51, 1.0, Base::bonded}), Catch::Contains("nu = 0.51"));
  CHECK_THROWS_WITH(ExactLayerKernel({1.0, 0.3, -1.0, Base::bonded}), Catch::Contains("h = -1"));
  CHECK_THROWS_WITH(ExactLayerKernel({0.0, 0.3, 1.0, Base::bonded}), Catch::Contains("E = 0"));
  ExactLayerOptions o;
  o.points_per_panel = 2;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("points_per_panel = 2"));
  o = ExactLayerOptions{};
  o.max_a_over_h = 0.0;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("max_a_over_h = 0"));
  const ExactLayerKernel k({1.0, 0.3, 1.0, Base::bonded}, range(5));
  CHECK_THROWS_WITH(k.solve(*p, 6.0), Catch::Contains("a/h = 6") && Catch::Contains("max_a_over_h"));
  CHECK_THROWS_AS(k.solve(*p, 0.0), DomainError);
  CHECK_THROWS_AS(k.flat_punch_factor(-1.0), DomainError);
}

TEST_CASE("exact layer pressure integrates to P_H and has the right limits", "[exact][pressure]") {
  boost::math::quadrature::tanh_sinh<double> ts;
  const auto p = make_paraboloid(100.0);
  for (double nu : {0.3, 0.5}) {
    const double Es = 1.0 / (1 - nu * nu);
    const ExactLayerKernel k({1.0, nu, 1.0, Base::bonded}, range(25));
    for (double a : {1e-3, 1.0, 5.0}) {
      const double P = ts.integrate(
          [&](double u) { return 2 * M_PI * a * a * u * k.pressure(*p, a, {a * u})[0]; }, 0.0, 1.0, 1e-9);
      INFO("nu=" << nu << " a/h=" << a);
      CHECK(rel_err(P, k.solve(*p, a).state.P_H) < 1e-8);
    }
    // Thick limit: Hertz, p = (2 E* / (pi R)) sqrt(a^2 - r^2).
    const double a = 1e-3;
    const auto pr = k.pressure(*p, a, {0.0, 0.5 * a, 0.9 * a});
    for (int i = 0; i < 3; ++i) {
      const double r = (i == 0 ? 0.0 : i == 1 ? 0.5 : 0.9) * a;
      CHECK(rel_err(pr[i], 2 * Es / (M_PI * 100.0) * std::sqrt(a * a - r * r)) < 2e-3);
    }
  }
  // Thin limit: the interior pressure approaches Winkler's K (delta - f(r)).
  const ThinLayerConstants c = thin_layer_constants({1.0, 0.3, 1.0, Base::bonded});
  const ExactLayerKernel k({1.0, 0.3, 1.0, Base::bonded}, range(25));
  const double a = 20.0, delta = k.solve(*p, a).state.delta_H;
  const auto pr = k.pressure(*p, a, {0.0, 10.0});
  CHECK(rel_err(pr[0], c.K * delta) < 0.03);
  CHECK(rel_err(pr[1], c.K * (delta - p->f(10.0))) < 0.03);
  CHECK_THROWS_WITH(k.pressure(*p, a, {a}), Catch::Contains("r = 20"));
  CHECK_THROWS_AS(k.pressure(*p, a, {-1.0}), DomainError);
}

TEST_CASE("edge correction: beta as theory.md s.6 reports, 10x better than Winkler", "[exact][edge]") {
  // theory.md s.6: beta ~ 0.12 (nu = 0.3), -0.11 (0.4), -0.55 (0.45), 0.18 (frictionless).
  CHECK(edge_correction_beta({1.0, 0.3, 1.0, Base::bonded}) == Approx(0.12).margin(0.01));
  CHECK(edge_correction_beta({1.0, 0.4, 1.0, Base::bonded}) == Approx(-0.11).margin(0.015));
  CHECK(edge_correction_beta({1.0, 0.45, 1.0, Base::bonded}) == Approx(-0.55).margin(0.05));
  CHECK(edge_correction_beta({1.0, 0.3, 1.0, Base::frictionless}) == Approx(0.18).margin(0.01));
  const auto p = make_paraboloid(100.0);
  for (const ElasticLayer layer : {ElasticLayer{1.0, 0.0, 1.0, Base::bonded},
                                   ElasticLayer{1.0, 0.3, 1.0, Base::bonded},
                                   ElasticLayer{1.0, 0.3, 1.0, Base::frictionless}}) {
    const auto edge = make_edge_corrected(p, layer);
    const auto winkler = make_winkler(p, thin_layer_constants(layer).K);
    const ExactLayerKernel k(layer, range(12));
    for (double a : {5.0, 10.0}) {
      const NonAdhesiveState e = k.solve(*p, a).state, c = edge->state(a), w = winkler->state(a);
      INFO("nu=" << layer.nu << " a/h=" << a);
      CHECK(std::abs(c.P_H / e.P_H - 1) < 0.1 * std::abs(w.P_H / e.P_H - 1));
      CHECK(std::abs(c.delta_H / e.delta_H - 1) < 0.1 * std::abs(w.delta_H / e.delta_H - 1));
      CHECK(c.a == a);
    }
    // Consistent: S = dP_H/d delta_H.
    auto g = [&](auto field) {
      auto f = [&](double x) { return field(edge->state(std::exp(x))); };
      return boost::math::differentiation::finite_difference_derivative<decltype(f), double, 6>(f, std::log(3.0));
    };
    CHECK(rel_err(g([](const NonAdhesiveState& s) { return s.P_H; }) / g([](const NonAdhesiveState& s) { return s.delta_H; }),
                  edge->state(3.0).S) < 1e-8);
  }
  CHECK_THROWS_WITH(edge_correction_beta({1.0, 0.5, 1.0, Base::bonded}), Catch::Contains("nu = 0.5"));
  const auto neg = make_edge_corrected(p, {1.0, 0.45, 1.0, Base::bonded});  // beta h = -0.5
  CHECK_THROWS_WITH(neg->state(0.4), Catch::Contains("effective radius"));
}

TEST_CASE("exact-layer searches stay inside the solver's a/h range", "[exact][contact]") {
  // Regression: the power law's bracket seed (its length scale, 240 h) lay beyond
  // max_a_over_h, and the search threw instead of treating the bound as the domain edge.
  const auto model = make_exact_layer(make_power_law(3e3, 2.5), {1e6, 0.3, 2e-5, Base::bonded}, range(100));
  CHECK(model->max_radius() == Approx(100 * 2e-5));
  const JkrSolution jkr(model, 0.01);
  REQUIRE(jkr.zero_load_radius());
  CHECK(*jkr.zero_load_radius() < 100 * 2e-5);
  REQUIRE(jkr.pull_off());
  CHECK(jkr.pull_off()->P < 0.0);
  CHECK_THROWS_WITH(jkr.contact_radius_at_force(1e6), Catch::Contains("a <= 0.002"));
}

TEST_CASE("exact layer: conjugate gradients agree with the dense Cholesky solve", "[exact][iterative]") {
  // Oracle: the dense factorisation of the same Nystrom system (dense_max_unknowns forces
  // one path or the other).
  const auto sphere = make_sphere(1e4);
  for (double nu : {0.0, 0.49, 0.5}) {
    for (Base base : {Base::bonded, Base::frictionless}) {
      ExactLayerOptions dense = range(200), iterative = range(200);
      dense.dense_max_unknowns = 100000;
      iterative.dense_max_unknowns = 1;
      const ElasticLayer layer{2.0, nu, 1.0, base};
      const ExactLayerKernel kd(layer, dense), ki(layer, iterative);
      for (double a : {0.3, 7.0, 60.0, 150.0}) {
        const NonAdhesiveState d = kd.state(*sphere, a), i = ki.state(*sphere, a);
        INFO("nu=" << nu << " bonded=" << (base == Base::bonded) << " a/h=" << a);
        const double tol = nu == 0.5 ? 1e-10 : 1e-12;  // conditioning ~0.2 (a/h)^3 at nu = 0.5
        CHECK(rel_err(i.P_H, d.P_H) < tol);
        CHECK(rel_err(i.delta_H, d.delta_H) < tol);
        CHECK(rel_err(i.S, d.S) < tol);
        CHECK(rel_err(i.dS_da, d.dS_da) < tol);
      }
    }
  }
  ExactLayerOptions bad;
  bad.dense_max_unknowns = 0;
  CHECK_THROWS_WITH(bad.validate(), Catch::Contains("dense_max_unknowns = 0"));
}

TEST_CASE("exact layer at a/h = 1000 approaches the edge-corrected thin layer as O(h/a)", "[exact][iterative]") {
  // Oracle: Winkler at a + beta h (theory.md s.6), whose residual against the exact layer
  // falls like h/a; at a/h = 300 and 1000 the exact layer is solved by conjugate gradients.
  const auto p = make_paraboloid(1e5);
  ExactLayerOptions o;
  o.tabulate_power_laws = false;
  for (Base base : {Base::bonded, Base::frictionless}) {
    const ElasticLayer layer{1.0, 0.3, 1.0, base};
    const auto exact = make_exact_layer(p, layer, o), thin = make_edge_corrected(p, layer);
    const double e300 = rel_err(exact->state(300.0).P_H, thin->state(300.0).P_H);
    const double e1000 = rel_err(exact->state(1000.0).P_H, thin->state(1000.0).P_H);
    INFO("bonded=" << (base == Base::bonded) << " err 300: " << e300 << " err 1000: " << e1000);
    CHECK(e1000 < (base == Base::bonded ? 1e-5 : 1e-7));
    CHECK(e300 / e1000 > 2.5);  // O(h/a): 10/3 in the limit
    CHECK(e300 / e1000 < 4.5);
  }
}
