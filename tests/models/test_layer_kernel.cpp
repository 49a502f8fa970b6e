// The exact layer's kernel representation against direct quadrature of the transform and
// against the closed-form limits of its Taylor coefficients.
#include <catch2/catch.hpp>

#include <cmath>

#include "models/layer_kernel.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using layerjkr::detail::LayerKernelFunction;

namespace {

struct Case {
  double nu;
  bool bonded;
};
const Case kCases[] = {{0.0, true}, {0.3, true}, {0.45, true}, {0.49, true}, {0.5, true},
                       {0.3, false}, {0.5, false}, {-0.5, true}};

}  // namespace

TEST_CASE("q = 1 - L: Taylor coefficients start 1, -L'(0)", "[exact][kernel]") {
  for (const Case& c : kCases) {
    const auto q = LayerKernelFunction::taylor_one_minus_L(c.nu, c.bonded, 6);
    const double kappa = 3.0 - 4.0 * c.nu;
    CHECK(q[0] == Approx(1.0).epsilon(1e-15));
    const double slope = c.bonded ? -4.0 * (kappa - 1.0) / ((kappa + 1.0) * (kappa + 1.0)) : -0.5;
    CHECK(q[1] == Approx(slope).margin(1e-15));
  }
  // The series summed at u = 0.1 reproduces the closed form: it converges for |u| below the
  // nearest complex zero of L's denominator (|u| > 1).
  for (const Case& c : kCases) {
    const auto q = LayerKernelFunction::taylor_one_minus_L(c.nu, c.bonded, 40);
    const double u = 0.1, kappa = 3.0 - 4.0 * c.nu, E = std::exp(-2.0 * u);
    const double closed =
        c.bonded ? E * (2.0 * kappa * E + (1 + 2 * u) * (1 + 2 * u) + kappa * kappa) /
                       (kappa * (1.0 + E * E) + (4.0 * u * u + 1.0 + kappa * kappa) * E)
                 : 2.0 * E * (1.0 - E + 2.0 * u) / (1.0 - E * E + 4.0 * u * E);
    double sum = 0.0;
    for (int k = 39; k >= 0; --k) sum = sum * u + q[static_cast<std::size_t>(k)];
    CHECK(sum == Approx(closed).epsilon(1e-14));
  }
}

TEST_CASE("Kernel table and asymptotic tail agree with direct quadrature", "[exact][kernel]") {
  for (const Case& c : kCases) {
    const LayerKernelFunction k(c.nu, c.bonded);
    double worst_near = 0.0, worst_far = 0.0;
    // Off-grid points on [0, 40] (the Chebyshev pieces) and beyond (the series).
    for (double s : {0.0, 0.013, 0.37, 0.999, 1.5, 2.71, 5.55, 9.99, 17.3, 33.3, 47.1, 63.99}) {
      worst_near = std::max(worst_near, std::abs(k.value(s) - LayerKernelFunction::direct(c.nu, c.bonded, s)));
      CHECK(k.value(-s) == k.value(s));
    }
    for (double s : {63.9, 64.0, 71.7, 150.0, 999.0}) {
      const double d = LayerKernelFunction::direct(c.nu, c.bonded, s);
      worst_far = std::max(worst_far, std::abs(k.value(s) - d));
    }
    INFO("nu = " << c.nu << (c.bonded ? " bonded" : " frictionless"));
    CHECK(worst_near < 3e-14);  // the double Ooura oracle's own error is ~1.5e-14
    CHECK(worst_far < 1e-15);
  }
}

TEST_CASE("Kernel derivative matches central differences on both sides of sigma = 64", "[exact][kernel]") {
  const LayerKernelFunction k(0.49, true);
  for (double s : {0.3, 3.7, 63.5, 64.5, 120.0}) {
    const double h = 1e-4 * std::max(1.0, s);
    const double fd = (k.value(s + h) - k.value(s - h)) / (2.0 * h);
    CHECK(k.derivative(s) == Approx(fd).epsilon(1e-6).margin(1e-14));
    CHECK(k.derivative(-s) == -k.derivative(s));
  }
}
