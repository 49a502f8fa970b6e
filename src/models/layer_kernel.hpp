// Internal: the exact layer's kernel Ft(sigma) = int_0^inf [1 - L(u)] cos(u sigma) du for one
// Poisson's ratio and base, in units of h (docs/exact-layer.md).
//
// Representation (built once, ~16 ms; then ~30 ns a value):
// * sigma < kNear (64): the closed-form transform of e^{-2u}(1 + gamma u), which carries
//   Ft's slow 1/sigma^2 tail, plus the transform of the smooth remainder, computed by GSL's
//   QAWO at Chebyshev points and held as Chebyshev series (GSL cheb, 21 points a piece) on
//   12 pieces whose width grows with sigma: the remainder's transform is singular only on the
//   imaginary axis (+-2i, +-4i, ...).
// * sigma > kNear: the asymptotic series Ft ~ sum_k (-1)^(k+1) q^(2k+1)(0) / sigma^(2k+2)
//   (integration by parts), q = 1 - L, with q's Taylor coefficients at u = 0 computed
//   exactly by power-series arithmetic. Its terms fall like (2k+1)! / (|u*| sigma)^(2k+2)
//   until 2k ~ |u*| sigma, |u*| being the nearest complex zero of L's denominator (0.739 for
//   an incompressible bonded layer: cos y = -y), so the smallest term is ~exp(-|u*| sigma):
//   1e-14 at sigma = 40 (measured, which is why the series starts at 64, not 40), 1e-20 at 64.
// Measured against a long-double Ooura Fourier quadrature of the whole transform: 3e-15
// absolute below 64, 6e-17 beyond (nu = 0.3, 0.5, both bases). The tests use the double
// Ooura rule, itself good to 1.5e-14 (tests/models/test_layer_kernel.cpp).
//
// A stack of layers (stack_symbol.hpp) has the same representation in units of its top
// layer's h1, built per stack: the subtracted model is q(0) e^{-2u} + (q'(0) + 2 q(0)) u e^{-2u}
// (q(0) = 1 - E1*/Es* on a half-space), q's Taylor coefficients come from a Cauchy integral
// of the symbol at complex u, and since q's nearest complex singularity moves in like h1/H
// (H: the stack's thickness) the Chebyshev pieces continue geometrically (x1.5, x4/3) up to
// the sigma where the asymptotic series is verified to 1e-16 (docs/exact-layer.md).
#pragma once

#include <memory>
#include <vector>

#include "layerjkr/layered_medium.hpp"

namespace layerjkr {
class Context;
}

namespace layerjkr::detail {

class StackSymbol;

class LayerKernelFunction {
 public:
  /// nu in (-1, 0.5]; bonded: the layer is bonded to the rigid base (else frictionless).
  LayerKernelFunction(double nu, bool bonded);
  /// A stack's kernel in units of its top layer's thickness.
  explicit LayerKernelFunction(const StackSymbol& symbol);
  /// The kernel whose serialized() numbers these are (the disk cache): bit-identical values.
  /// Throws NumericalError if they are not a kernel's.
  explicit LayerKernelFunction(const std::vector<double>& serialized);
  /// Every number the kernel is made of, in a layout the constructor above reads back.
  std::vector<double> serialized() const;
  ~LayerKernelFunction();
  LayerKernelFunction(const LayerKernelFunction&) = delete;
  LayerKernelFunction& operator=(const LayerKernelFunction&) = delete;

  /// Ft(sigma), even; any finite sigma (below near() where there is no tail).
  double value(double sigma) const;
  /// dFt/dsigma, odd.
  double derivative(double sigma) const;

  /// The Chebyshev tables of a single layer reach sigma = kNear; the asymptotic series
  /// takes over beyond. A stack's reach further: near().
  static constexpr double kNear = 64.0;
  /// A stack's table reaches at most this far: no solve asks beyond 2 max_a_over_h (<= 2000).
  static constexpr double kMaxSigma = 2048.0;
  double near() const { return near_; }
  /// False when the asymptotic series could not be verified by kMaxSigma: then |sigma| < near()
  /// only (DomainError beyond).
  bool has_tail() const { return !tail_.empty(); }
  /// Number of Chebyshev pieces (12 for one layer).
  std::size_t pieces() const;

  /// Ft(sigma) by Boost's Ooura double-exponential Fourier quadrature of the whole
  /// transform (the tests' independent oracle; ~0.1 ms a value).
  static double direct(double nu, bool bonded, double sigma);
  /// The same for a stack's symbol.
  static double direct(const StackSymbol& symbol, double sigma);
  /// q(u) = 1 - L(u) of one layer in closed form (theory.md s.4), u >= 0.
  static double one_minus_L(double nu, bool bonded, double u);
  /// Taylor coefficients q_n of q(u) = 1 - L(u) at u = 0, n = 0..count-1 (q_0 = 1).
  static std::vector<double> taylor_one_minus_L(double nu, bool bonded, int count);

 private:
  struct Pieces;
  // Chebyshev tables of the remainder's transform on breaks_, model A, B, the tail.
  // size: the transform's scale (its quadrature's absolute tolerance is relative to it).
  template <class Q>
  void build(const Q& q, const std::vector<double>& splits, double size);
  [[noreturn]] void beyond_table(double sigma) const;
  double model_a_ = 1.0, model_b_ = 0.0;  // q ~ (A + B u) e^{-2u} is subtracted
  double near_ = kNear;
  std::vector<double> breaks_;
  std::vector<double> tail_;  // tail_[k] = (-1)^(k+1) q^(2k+1)(0)
  std::unique_ptr<Pieces> pieces_;
};

/// The kernel function for (nu, base) from `context`'s cache (null: Context::global()),
/// built on first request, once, thread-safely.
std::shared_ptr<const LayerKernelFunction> shared_layer_kernel(double nu, bool bonded,
                                                               const std::shared_ptr<Context>& context);
/// The kernel function of a stack from `context`'s cache, keyed by the stack's dimensionless
/// signature; a single layer on a rigid base is shared_layer_kernel's.
std::shared_ptr<const LayerKernelFunction> shared_stack_kernel(const LayeredMedium& medium,
                                                               const std::shared_ptr<Context>& context);

}  // namespace layerjkr::detail
