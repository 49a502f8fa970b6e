// Internal: the transforms the exact layer's kernel is built from (layer_kernel.cpp): the cosine
// transform of its symbol by GSL's QAWO, and the size of the symbol that sets its tolerance.
#pragma once

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace layerjkr::detail {

/// int_0^inf fn(u) cos(sigma u) du for fn decaying like u^2 e^{-2u}: the tail beyond u = 40 is
/// below 1e-30, so GSL's QAWO on [0, 40] (QAG at sigma = 0) is used, split at `splits` (a stack's
/// switch points, where its symbol has a rounding-size step). `levels`: the bisections QAWO's
/// table of moments covers (each costs its set-up; a stack's segments between switch points need
/// few, and 30 halve its kernel's build against 60). `scale` is the size of fn near 0 (1 for one
/// layer; |q(0)| = E1*/Es* - 1 for a stiff film on a soft substrate): the tolerances are relative
/// to it. Throws NumericalError naming sigma and the segment where GSL fails.
double cosine_transform(gsl_function fn, double sigma, const std::vector<double>& splits, double scale, int levels);

// int_0^40 |q(u)| du to a few digits, split where q changes: the size of the transform, which
// sets the quadrature's absolute tolerance (a thick soft stack has |q| ~ 1e6 where one layer
// has 1).
template <class Q>
double integral_of_abs(const Q& q, const std::vector<double>& splits) {
  std::vector<double> edges{0.0};
  for (double x : splits)
    if (x > 0.0 && x < 40.0) edges.push_back(x);
  edges.push_back(40.0);
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    // Geometric nodes within each segment (q's features there are on log scales), midpoint rule.
    const double a = std::max(edges[i], 1e-3 * edges[i + 1]), b = edges[i + 1];
    constexpr int kNodes = 64;
    for (int k = 0; k < kNodes; ++k) {
      const double lo = a * std::pow(b / a, static_cast<double>(k) / kNodes), hi = a * std::pow(b / a, (k + 1.0) / kNodes);
      total += std::abs(q(0.5 * (lo + hi))) * (hi - lo);
    }
    total += std::abs(q(0.5 * a)) * (a - edges[i]);
  }
  return total;
}

}  // namespace layerjkr::detail
