// The layered medium's symbol L(u) (src/models/stack_symbol.cpp) against an independent
// solution (Papkovich-Neuber potentials in mpmath: tools/stack_reference.py), the single
// layer's closed form, and the limits a stack must reach.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model.hpp"
#include "models/layer_kernel.hpp"
#include "models/stack_symbol.hpp"
#include "support/stack_media.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using layerjkr::Base;
using layerjkr::LayeredMedium;
using layerjkr::StackLayer;
using layerjkr::detail::LayerKernelFunction;
using layerjkr::detail::StackSymbol;

using test::on_half_space;
using test::stack;

namespace {

// The cases of tools/stack_reference.py, by name.
std::map<std::string, LayeredMedium> reference_cases() {
  return {
      {"one_bonded_incompressible", stack({{1.0, 0.5, 1.0}})},
      {"appendix_a_bilayer", stack({{3e6, 0.3, 0.1e-3}, {300e6, 0.3, 1.9e-3}})},
      {"three_frictionless", stack({{1.0, 0.3, 1.0}, {20.0, 0.5, 0.5}, {0.1, 0.45, 2.0}}, Base::frictionless)},
      {"three_bonded_incompressible", stack({{1.0, 0.5, 1.0}, {5.0, 0.5, 0.5}, {0.3, 0.5, 2.0}})},
      {"stiff_film_on_half_space", on_half_space({{100.0, 0.3, 1.0}, {2.0, 0.5, 0.7}}, 1.0, 0.49)},
      {"soft_film_on_half_space", on_half_space({{0.05, 0.5, 1.0}, {2.0, 0.2, 3.0}}, 1.0, 0.5)},
      {"layer_on_stiffer_half_space", on_half_space({{1.0, 0.4, 1.0}}, 10.0, 0.3)},
  };
}

std::vector<double> log_grid(double lo, double hi, int n) {
  std::vector<double> u;
  for (int i = 0; i < n; ++i) u.push_back(lo * std::pow(hi / lo, i / (n - 1.0)));
  return u;
}

double M_modulus(const StackLayer& l) {  // P-wave modulus lambda + 2 mu (infinite at nu = 1/2)
  return l.E * (1.0 - l.nu) / ((1.0 + l.nu) * (1.0 - 2.0 * l.nu));
}
double mu(double E, double nu) { return E / (2.0 * (1.0 + nu)); }
double E_star(double E, double nu) { return E / (1.0 - nu * nu); }

}  // namespace

TEST_CASE("Stack symbol against the Papkovich-Neuber global solve in mpmath", "[stack]") {
  const auto cases = reference_cases();
  std::map<std::string, StackSymbol> symbols;
  for (const auto& [name, medium] : cases) symbols.emplace(name, StackSymbol(medium));
  int rows = 0;
  double worst_L = 0.0, worst_q = 0.0;
  for (const auto& [name, v] : test::read_reference_rows(std::string(LAYERJKR_SOURCE_DIR) +
                                                                    "/data/stack/symbol_reference.csv")) {
    REQUIRE(v.size() == 3);
    const auto it = symbols.find(name);
    REQUIRE(it != symbols.end());
    double L = 0.0, q = 0.0;
    it->second.evaluate(v[0], L, q);
    INFO(name << " u = " << v[0] << ": L = " << L << " (ref " << v[1] << "), q = " << q << " (ref " << v[2] << ")");
    worst_L = std::max(worst_L, std::abs(L / v[1] - 1.0));
    CHECK(std::abs(L / v[1] - 1.0) < 1e-13);
    // q keeps relative accuracy even where it is 1e-18 (u = 24)
    if (v[0] >= 5.0) {
      worst_q = std::max(worst_q, std::abs(q / v[2] - 1.0));
      CHECK(std::abs(q / v[2] - 1.0) < 1e-11);
    }
    ++rows;
  }
  CHECK(rows == 77);
  CAPTURE(worst_L, worst_q);
  CHECK(worst_L < 1e-13);
}

TEST_CASE("One layer: the stack symbol is the library's closed form", "[stack]") {
  for (const Base base : {Base::bonded, Base::frictionless})
    for (const double nu : {0.3, 0.49, 0.5, 0.0, -0.5}) {
      const StackSymbol s(stack({{7.0, nu, 0.3}}, base));
      double worst = 0.0;
      for (double u : log_grid(1e-6, 1e4, 801))
        worst = std::max(worst, std::abs(s.q(u) - LayerKernelFunction::one_minus_L(nu, base == Base::bonded, u)));
      INFO("nu = " << nu << (base == Base::bonded ? " bonded" : " frictionless"));
      CHECK(worst < 1e-15);
      const auto t = s.taylor(9, 0.25);
      const auto lib = LayerKernelFunction::taylor_one_minus_L(nu, base == Base::bonded, 9);
      for (std::size_t k = 0; k < t.size(); ++k) CHECK(std::abs(t[k] - lib[k]) * std::pow(0.25, k) < 1e-15);
      CHECK(layerjkr::stack_compliance_ratio(stack({{7.0, nu, 0.3}}, base), 0.7) ==
            Approx(1.0 - LayerKernelFunction::one_minus_L(nu, base == Base::bonded, 0.7)).epsilon(1e-15));
    }
}

TEST_CASE("Identical layers equal one thick layer", "[stack]") {
  std::vector<LayeredMedium> bases = {stack({}), stack({}, Base::frictionless), on_half_space({}, 7.0, 0.25)};
  for (const LayeredMedium& b : bases)
    for (const double nu : {0.3, 0.5}) {
      auto with = [&](std::vector<StackLayer> l) {
        LayeredMedium m = b;
        m.layers = std::move(l);
        return StackSymbol(m);
      };
      const StackSymbol one = with({{2.0, nu, 1.0}});
      const StackSymbol two = with({{2.0, nu, 0.5}, {2.0, nu, 0.5}});
      const StackSymbol three = with({{2.0, nu, 1.0 / 3}, {2.0, nu, 1.0 / 3}, {2.0, nu, 1.0 / 3}});
      double worst = 0.0;
      for (double u : log_grid(1e-6, 1e4, 401)) {  // u = k h1: the same k is u/2, u/3
        worst = std::max(worst, std::abs(two.L(u / 2) / one.L(u) - 1.0));
        worst = std::max(worst, std::abs(three.L(u / 3) / one.L(u) - 1.0));
      }
      CHECK(worst < 1e-13);
    }
}

TEST_CASE("A stiff lower layer acts as a rigid bonded base", "[stack]") {
  for (const double nu : {0.3, 0.5}) {
    const StackSymbol rigid(stack({{1.0, nu, 1.0}}));
    for (const double ratio : {1e6, 1e10}) {
      std::vector<LayeredMedium> media = {stack({{1.0, nu, 1.0}, {ratio, 0.3, 2.0}}),
                                          stack({{1.0, nu, 1.0}, {ratio, 0.3, 2.0}}, Base::frictionless),
                                          on_half_space({{1.0, nu, 1.0}, {ratio, 0.3, 2.0}}, ratio, 0.3)};
      for (const LayeredMedium& m : media) {
        const StackSymbol s(m);
        double worst = 0.0;
        for (double u : log_grid(1e-6, 1e4, 401)) worst = std::max(worst, std::abs(s.L(u) - rigid.L(u)));
        CHECK(worst < 10.0 / ratio);  // the difference is ~E1/E2
        CHECK(worst > 0.01 / ratio);
      }
    }
  }
}

TEST_CASE("Half-space of the top layer's material, and large k", "[stack]") {
  for (const double nu : {0.0, 0.3, 0.49, 0.5}) {
    const StackSymbol one(on_half_space({{3.0, nu, 1.0}}, 3.0, nu));
    const StackSymbol two(on_half_space({{3.0, nu, 1.0}, {3.0, nu, 0.3}}, 3.0, nu));
    for (double u : log_grid(1e-6, 1e4, 201)) {
      CHECK(std::abs(one.L(u) - 1.0) < 1e-14);
      CHECK(std::abs(two.L(u) - 1.0) < 1e-14);
    }
    CHECK(one.q0() == Approx(0.0).margin(1e-15));
  }
  for (const auto& [name, medium] : reference_cases()) {
    const StackSymbol s(medium);
    for (double u : {40.0, 60.0, 1e3, 1e4}) CHECK(std::abs(s.L(u) - 1.0) < 1e-15);
  }
}

TEST_CASE("No NaN, overflow or non-positive L for u in [1e-6, 1e4]", "[stack]") {
  std::vector<LayeredMedium> media;
  for (const auto& [name, medium] : reference_cases()) media.push_back(medium);
  media.push_back(stack({{1.0, 0.5, 1.0}, {1e10, 0.5, 100.0}, {1e-2, 0.2, 1e-3}}));
  media.push_back(on_half_space({{1e5, 0.2, 1.0}, {1.0, 0.5, 1e3}}, 1e-5, 0.5));
  media.push_back(stack({{1.0, -0.9, 1.0}, {1e-6, 0.5, 10.0}}, Base::frictionless));
  for (const LayeredMedium& m : media) {
    const StackSymbol s(m);
    int bad = 0;
    for (double u : log_grid(1e-6, 1e4, 1001)) {
      double L = 0.0, q = 0.0;
      s.evaluate(u, L, q);
      if (!std::isfinite(L) || !std::isfinite(q) || !(L > 0.0)) ++bad;
    }
    CHECK(bad == 0);
  }
}

TEST_CASE("Small k: springs in series, the frictionless laminate, squeeze flow, the substrate", "[stack]") {
  const std::vector<std::vector<StackLayer>> stacks = {{{1.0, 0.3, 1.0}, {300.0, 0.3, 19.0}},
                                                       {{1.0, 0.5, 1.0}, {3.0, 0.2, 2.0}, {0.5, 0.45, 0.5}},
                                                       {{1.0, 0.3, 1.0}, {0.5, 0.5, 2.0}}};
  for (const auto& layers : stacks) {
    const double u = 1e-7, h1 = layers[0].h, E1s = E_star(layers[0].E, layers[0].nu);
    // bonded: C(0) = sum h_i/M_i (an incompressible layer is rigid in compression)
    double eps = 0.0, b = 0.0, c = 0.0;
    for (const StackLayer& l : layers) {
      if (l.nu < 0.5) eps += l.h / M_modulus(l);
      b += l.h * l.nu / (1.0 - l.nu);
      c += l.h * 2.0 * mu(l.E, l.nu) / (1.0 - l.nu);
    }
    CHECK(StackSymbol(stack(layers)).L(u) / u == Approx(E1s / (2.0 * h1) * eps).epsilon(1e-5));
    // frictionless: the layers stretch together, in-plane force zero
    CHECK(StackSymbol(stack(layers, Base::frictionless)).L(u) / u ==
          Approx(E1s / (2.0 * h1) * (eps + b * b / c)).epsilon(1e-5));
  }
  {  // every layer incompressible: w = -J lap p, J = int z^2/mu dz
    const std::vector<StackLayer> layers = {{1.0, 0.5, 1.0}, {6.0, 0.5, 0.5}, {0.4, 0.5, 2.0}};
    double z0 = 0.0, J = 0.0;
    for (const StackLayer& l : layers) {
      J += (std::pow(z0 + l.h, 3) - std::pow(z0, 3)) / (3.0 * mu(l.E, l.nu));
      z0 += l.h;
    }
    const double u = 1e-5;
    CHECK(StackSymbol(stack(layers)).L(u) / (u * u * u) == Approx(E_star(1.0, 0.5) / 2.0 * J).epsilon(1e-6));
  }
  // half-space: C(k) = 2/(Es* k) + C1 + O(k)
  struct HS {
    std::vector<StackLayer> layers;
    double Es, nus;
  };
  for (const HS& c : {HS{{{1.0, 0.3, 1.0}}, 7.0, 0.25}, HS{{{1.0, 0.5, 1.0}, {0.1, 0.3, 1.0}}, 0.5, 0.5}}) {
    const StackSymbol s(on_half_space(c.layers, c.Es, c.nus));
    const double L0 = E_star(c.layers[0].E, c.layers[0].nu) / E_star(c.Es, c.nus);
    CHECK(s.L(1e-9) == Approx(L0).epsilon(1e-7));
    CHECK(1.0 - s.q0() == Approx(L0).epsilon(1e-15));
    const double ms = mu(c.Es, c.nus);
    double C1 = 0.0;
    for (const StackLayer& l : c.layers) {
      const double m = mu(l.E, l.nu);
      C1 += l.h * (m * (1 - 2 * c.nus) + ms) * (ms * (1 - 2 * l.nu) - m * (1 - 2 * c.nus)) /
            (2 * m * ms * ms * (1 - l.nu));
    }
    const double u = 1e-6;
    CHECK((s.L(u) - L0) / u == Approx(E_star(c.layers[0].E, c.layers[0].nu) / 2.0 * C1).epsilon(1e-4));
  }
}

TEST_CASE("Invalid stacks name the layer and the key", "[stack]") {
  auto message = [](const LayeredMedium& m) {
    try {
      StackSymbol s(m, "test");
    } catch (const layerjkr::DomainError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(message(stack({})), Catch::Contains("layers"));
  CHECK_THAT(message(stack({{1.0, 0.3, 1.0}, {1.0, 0.3, 0.0}})), Catch::Contains("layers[1].h"));
  CHECK_THAT(message(stack({{1.0, 0.51, 1.0}})), Catch::Contains("layers[0].nu"));
  CHECK_THAT(message(stack({{-1.0, 0.3, 1.0}})), Catch::Contains("layers[0].E"));
  CHECK_THAT(message(on_half_space({{1.0, 0.3, 1.0}}, 1.0, -1.0)), Catch::Contains("substrate.nu"));
}

TEST_CASE("Thin-stack constants: the library's one-layer laws, and the symbol's expansion", "[stack][thin]") {
  for (const double nu : {0.0, 0.2, 0.3, 0.45}) {
    const layerjkr::ElasticLayer layer{2.0, nu, 0.3, Base::bonded};
    const auto c = layerjkr::thin_stack_constants(LayeredMedium::single(layer));
    const auto lib = layerjkr::thin_layer_constants(layer);
    CHECK(c.K == Approx(lib.K).epsilon(1e-14));
    CHECK(c.G == Approx(lib.G).epsilon(1e-13).margin(1e-15));
    const auto frictionless = layerjkr::thin_stack_constants(LayeredMedium::single({2.0, nu, 0.3, Base::frictionless}));
    CHECK(frictionless.K == Approx(layerjkr::thin_layer_constants({2.0, nu, 0.3, Base::frictionless}).K).epsilon(1e-14));
  }
  for (const double nu : {0.3, 0.49, 0.5}) {  // the uniform law's (eps, D), finite at nu = 1/2
    const layerjkr::ElasticLayer layer{2.0, nu, 0.3, Base::bonded};
    const auto c = layerjkr::thin_stack_constants(LayeredMedium::single(layer));
    const auto u = layerjkr::uniform_layer_constants(layer);
    CHECK(c.eps == Approx(u.eps).margin(1e-16));
    CHECK(c.D == Approx(u.D).epsilon(1e-13));
  }
  // C(k) = eps + D k^2 + O(k^4) against the exact symbol (Richardson in k), bonded base
  for (const auto& layers : std::vector<std::vector<StackLayer>>{{{3e6, 0.3, 0.1e-3}, {300e6, 0.3, 1.9e-3}},
                                                                 {{1.0, 0.3, 1.0}, {5.0, 0.45, 0.5}, {0.3, 0.2, 2.0}},
                                                                 {{1.0, 0.3, 1.0}, {0.5, 0.5, 1.0}},
                                                                 {{1.0, 0.5, 1.0}, {6.0, 0.5, 0.5}, {0.4, 0.5, 2.0}}}) {
    const LayeredMedium m = stack(layers);
    const auto c = layerjkr::thin_stack_constants(m);
    const StackSymbol s(m);
    const double h1 = layers[0].h, E1s = E_star(layers[0].E, layers[0].nu);
    double H = 0.0;
    for (const StackLayer& l : layers) H += l.h;
    auto R = [&](double k) { return (2.0 * s.L(k * h1) / (E1s * k) - c.eps) / (k * k); };
    const double k = 3e-3 / H;
    const double D = (4.0 * R(k / 2) - R(k)) / 3.0;
    CHECK(D == Approx(c.D).epsilon(1e-6));
    CHECK(c.K == Approx(1.0 / c.eps));
    // frictionless base: C(0), the laminate
    const LayeredMedium f = stack(layers, Base::frictionless);
    const double u = 1e-7;
    CHECK(2.0 * StackSymbol(f).L(u) / (E1s * u / h1) == Approx(c.frictionless).epsilon(1e-5));
    CHECK(layerjkr::thin_stack_constants(f).K == Approx(1.0 / c.frictionless).epsilon(1e-15));
  }
  {  // every layer incompressible: eps = 0 and D = J = int z^2/mu dz
    const std::vector<StackLayer> layers = {{1.0, 0.5, 1.0}, {6.0, 0.5, 0.5}, {0.4, 0.5, 2.0}};
    const auto c = layerjkr::thin_stack_constants(stack(layers));
    double z0 = 0.0, J = 0.0;
    for (const StackLayer& l : layers) {
      J += (std::pow(z0 + l.h, 3) - std::pow(z0, 3)) / (3.0 * mu(l.E, l.nu));
      z0 += l.h;
    }
    CHECK(c.eps == 0.0);
    CHECK(c.D == Approx(J).epsilon(1e-14));
    CHECK(std::isinf(c.K));
  }
  CHECK_THROWS_WITH(layerjkr::thin_stack_constants(on_half_space({{1.0, 0.3, 1.0}}, 1.0, 0.3)),
                    Catch::Contains("no thin-layer law"));
}
