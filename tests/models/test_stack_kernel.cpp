// A stack's kernel Ft(sigma) (layer_kernel.hpp built from stack_symbol.hpp) against direct
// quadrature of its transform, and against the single layer's kernel for one layer.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/layered_medium.hpp"
#include "models/layer_kernel.hpp"
#include "models/stack_symbol.hpp"
#include "support/stack_media.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using layerjkr::Base;
using layerjkr::LayeredMedium;
using layerjkr::detail::LayerKernelFunction;
using layerjkr::detail::StackSymbol;

using test::on_half_space;
using test::stack;

TEST_CASE("One layer: the stack-built kernel equals the single layer's", "[stack][kernel]") {
  struct Case {
    double nu;
    Base base;
  };
  for (const Case c : {Case{0.3, Base::bonded}, Case{0.5, Base::bonded}, Case{0.3, Base::frictionless}}) {
    const StackSymbol symbol(stack({{2.0, c.nu, 0.1}}, c.base));
    const LayerKernelFunction from_stack(symbol);
    const LayerKernelFunction single(c.nu, c.base == Base::bonded);
    double worst = 0.0, worst_slope = 0.0;
    for (double s = 0.0; s < 2500.0; s = s * 1.07 + 0.011) {
      worst = std::max(worst, std::abs(from_stack.value(s) - single.value(s)));
      worst_slope = std::max(worst_slope, std::abs(from_stack.derivative(s) - single.derivative(s)));
    }
    INFO("nu = " << c.nu << ", pieces " << from_stack.pieces() << ", tail from " << from_stack.near());
    CHECK(worst < 3e-15);
    CHECK(worst_slope < 1e-13);
  }
}

TEST_CASE("Stack kernels agree with direct quadrature of the transform", "[stack][kernel]") {
  const std::vector<LayeredMedium> media = {
      stack({{3e6, 0.3, 0.1e-3}, {300e6, 0.3, 1.9e-3}}),  // the paper's Appendix A
      stack({{1.0, 0.3, 1.0}, {20.0, 0.5, 0.5}, {0.1, 0.45, 2.0}}, Base::frictionless),
      on_half_space({{0.05, 0.5, 1.0}, {2.0, 0.2, 3.0}}, 1.0, 0.5),
      on_half_space({{100.0, 0.3, 1.0}, {2.0, 0.5, 0.7}}, 1.0, 0.49),
      on_half_space({{1.0, 0.4, 1.0}}, 10.0, 0.3),
  };
  for (const LayeredMedium& m : media) {
    const StackSymbol symbol(m);
    const LayerKernelFunction k(symbol);
    const double near = k.near();
    // the size of q near 0: 1 on rigid bases, E1*/Es* - 1 for a stiff film on a soft substrate
    const double scale = std::max(1.0, std::abs(symbol.q0()));
    INFO("stack of " << m.layers.size() << " layers: " << k.pieces() << " pieces, tail from sigma = " << near);
    double worst = 0.0;
    std::vector<double> sigmas{0.0, 0.013, 0.37, 1.5, 5.55, 17.3, 47.1, 99.9, 333.3, 0.71 * near, 0.999 * near};
    if (k.has_tail()) {
      sigmas.insert(sigmas.end(), {1.001 * near, 1.7 * near, 4.0 * near});
    } else {  // the table reaches every sigma a solve asks for (2 max_a_over_h <= 2000), and no further
      CHECK(near == LayerKernelFunction::kMaxSigma);
      CHECK_THROWS_AS(k.value(1.001 * near), layerjkr::DomainError);
    }
    for (double s : sigmas) {
      const double d = LayerKernelFunction::direct(symbol, s);
      INFO("sigma = " << s << ": table " << k.value(s) << ", direct " << d);
      CHECK(std::abs(k.value(s) - d) < 3e-14 * scale);
      CHECK(k.value(-s) == k.value(s));
      worst = std::max(worst, std::abs(k.value(s) - d));
    }
    CAPTURE(worst);
    // the slope against a central difference of the values
    for (double s : {0.5, 3.3, 31.0, 0.5 * near, k.has_tail() ? 2.0 * near : 0.9 * near}) {
      const double e = 1e-4 * std::max(1.0, s);
      const double fd = (k.value(s + e) - k.value(s - e)) / (2.0 * e);
      CHECK(k.derivative(s) == Approx(fd).margin(1e-9 * scale));
      CHECK(k.derivative(-s) == -k.derivative(s));
    }
  }
}
