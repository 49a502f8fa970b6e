// Internal: the surface-compliance symbol L(u) of a stack of bonded layers and its kernel
// symbol q(u) = 1 - L(u), u = k h1 (layered_medium.hpp, docs/theory.md s.4a).
//
// Hankel-space state y = (U, W, t, s) = (u_r, u_z, tau_rz/(mu1 k), sigma_zz/(mu1 k)); in a
// layer y' = A(nu) y with (A^2 - I)^2 = 0, so exp(A x) is a closed form. Everything below an
// interface is a 2-dim subspace, kept as [F; I] (F: the 2x2 flexibility). Going up through a
// layer of thickness x = k h_i:
// * x <= 1: the propagator Q(x) = e^{-x} exp(-A x) (only e^{-2x} and series without
//   cancellation appear), keeping L's relative accuracy as u -> 0;
// * x > 1: the layer's reflection matrix R_top = e^{-2x}(I - x n+) R (I + x n-), whose
//   n+- do not depend on nu: nothing grows, and q = 1 - L comes straight from R (relative
//   accuracy as q ~ u^2 e^{-2u} -> 0).
#pragma once

#include <complex>
#include <vector>

#include "layerjkr/layered_medium.hpp"

namespace layerjkr::detail {

class StackSymbol {
 public:
  /// Validates `medium` (DomainError naming layers[i].key); only ratios to the top layer are kept.
  StackSymbol(const LayeredMedium& medium, const char* function = "StackSymbol");

  /// L(u) and q(u) = 1 - L(u) for u >= 0, each computed where it keeps relative accuracy.
  void evaluate(double u, double& L, double& q) const;
  double L(double u) const;
  double q(double u) const;
  /// q at complex u by the propagator form only (|u| H/h1 of order 1 at most): for Taylor
  /// coefficients by a Cauchy integral.
  std::complex<double> q(std::complex<double> u) const;

  /// The u where a layer switches from the propagator to the reflection form (k h_i = 1),
  /// ascending: q is analytic across them but carries a rounding-size step there.
  std::vector<double> switch_points() const;
  /// q(0): 1 on a rigid base, 1 - E1*/Es* on a half-space.
  double q0() const { return q0_; }
  /// Taylor coefficients q_n, n < count, of q at 0 from `points` values on |u| = rho.
  std::vector<double> taylor(int count, double rho, int points = 256) const;
  /// H/h1: the total thickness in units of the top layer's.
  double total_thickness() const { return total_; }
  /// Largest shear modulus of the layers over the substrate's (0 on a rigid base).
  double max_layer_over_substrate() const { return stiff_film_; }

  /// What L depends on: the base, nu1, and (E_i/E1, nu_i, h_i/h1) for i > 1, (Es/E1, nu_s).
  /// Equal signatures have equal symbols (the kernel cache's key).
  const std::vector<double>& signature() const { return signature_; }

  enum class BaseKind { bonded, frictionless, half_space };

  struct Layer {
    double nu, m, r;     // Poisson's ratio, mu_i/mu1, h_i/h1
    double A[4][4], N[4][4], AN[4][4];
  };

 private:
  template <class T>
  void propagate(T u, T& L, T& q, bool reflection_allowed) const;

  std::vector<Layer> layers_;  // top first
  BaseKind base_ = BaseKind::bonded;
  double ms_ = 0.0, nus_ = 0.0;  // substrate: mu_s/mu1, nu_s
  double q0_ = 1.0, total_ = 1.0, stiff_film_ = 0.0;
  std::vector<double> signature_;
};

}  // namespace layerjkr::detail
