// layerjkr: the exact elastic layer - frictionless axisymmetric indentation of a layer
// (E, nu, h) bonded to, or lying frictionless on, a rigid base (docs/theory.md s.4).
//
// The contact is reduced to a second-kind Fredholm equation for an auxiliary function
// g on [0, a]:
//   g(x) - (1/pi) int_0^a g(t) [F(x-t) + F(x+t)] dt = (E*/pi) D(x),
//   F(s) = (1/h) Ft(|s|/h),  Ft(sigma) = int_0^inf [1 - L(u)] cos(u sigma) du,
//   D(x) = delta - x I0(x)   (I0: the profile's Sneddon integral).
// By linearity g = (E*/pi)(delta phi0 - phi_f), with phi0 the flat-punch solution.
// Then delta_H = phi_f(a)/phi0(a) (from g(a) = 0), S = 2E* int phi0,
// S' = 2E* phi0(a)^2 and P_H = 2E* (delta_H int phi0 - int phi_f).
//
// Numerics, all in units of h:
// * Ft, for sigma <= 64: the closed-form transform of e^{-2u}(1 + c u), which carries Ft's
//   slow 1/sigma^2 tail, plus a Chebyshev table of the smooth remainder's transform (GSL
//   QAWO at Chebyshev points); beyond 64, the asymptotic series of Ft in 1/sigma^2 from the
//   Taylor coefficients of 1 - L(u) at u = 0. Accurate to ~1e-14 absolute; built once per
//   (nu, base) in ~16 ms and shared by every kernel.
// * Nystrom method with composite Gauss-Legendre panels no wider than `panel_width` h,
//   symmetrised and factored by Cholesky (Eigen LLT); above `dense_max_unknowns`, solved by
//   conjugate gradients with FFT Toeplitz/Hankel products and a two-level preconditioner.
// * solve() computes a state twice, with p and 3p/4 nodes a panel. The difference is the returned
//   error estimate, as quadrature::tanh_sinh does.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "layerjkr/context.hpp"
#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {
namespace detail {
class LayerKernelFunction;
}

struct ExactLayerOptions {
  /// Largest contact radius the solver accepts, in units of h (> 0, <= 1000).
  double max_a_over_h = 1000.0;
  /// Gauss-Legendre nodes per panel (4..32). The defaults (16 nodes on 3h panels) come from
  /// the measured convergence study (docs/data/exact_layer_convergence.md).
  int points_per_panel = 16;
  /// Panel width in units of h (0 < width <= 8).
  double panel_width = 3.0;
  /// Systems with more unknowns (panels x nodes) are solved by two-level preconditioned
  /// conjugate gradients with FFT products instead of a dense Cholesky factor (>= 1; the
  /// crossover measured in bench/exact_layer_scaling.cpp). Sweeps always factor.
  int dense_max_unknowns = 500;
  /// Minimum number of panels (>= 2).
  int min_panels = 4;
  /// ContactModel "exact" with a paraboloid, cone or power law: take states from the shared
  /// per-(nu, base, d) table in ln(a/h) (~0.2 us a state; each unit piece of ln(a/h) is built
  /// on first use by 13 solves) instead of solving each radius. Covers a/h in [1e-6, 220].
  bool tabulate_power_laws = true;
  /// Solve a second time with 3/4 of the nodes per panel to estimate the error (about +45 %
  /// cost). The estimate is that of the coarser solve, so it bounds the returned error.
  bool estimate_error = true;
  /// Where the kernel functions and power-law tables come from and are cached; null (the
  /// default): Context::global(). Read when a solver or model is built: they keep what they
  /// took from it, not the Context itself (ExactLayerKernel::options() returns this null).
  std::shared_ptr<Context> context;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// One non-adhesive state with error estimates: |fine - coarse| / |fine|, the error of the
/// coarser solve, which with spectral convergence is orders above that of the returned one.
struct ExactLayerState {
  NonAdhesiveState state;
  double P_H_error = 0.0;      ///< estimated relative error of P_H (NaN if not estimated)
  double delta_H_error = 0.0;  ///< estimated relative error of delta_H (NaN if not estimated)
  double S_error = 0.0;        ///< estimated relative error of S (NaN if not estimated)
  int unknowns = 0;            ///< Nystrom nodes of the fine solve
};

/// The exact-layer solver for one layer (E, nu, h, base). The kernel function depends only
/// on nu and the base; it is built once per Context (~16 ms; ExactLayerOptions::context) and
/// shared. nu in (-1, 0.5]
/// (0.5: incompressible, bonded or frictionless), E > 0, h > 0.
class ExactLayerKernel {
 public:
  ExactLayerKernel(const ElasticLayer& layer, ExactLayerOptions options = {});
  /// A stack of layers (layered_medium.hpp): everything below holds with E* -> E1* and
  /// h -> h1 of the top layer (a/h is a/h1, kernel() in units of h1). The kernel function is
  /// built per stack (0.1-0.3 s, docs/exact-layer.md) and shared through the Context by the
  /// stack's ratios; a state then costs what one of a single layer of thickness h1 costs.
  ExactLayerKernel(const LayeredMedium& medium, ExactLayerOptions options = {});
  ~ExactLayerKernel();
  ExactLayerKernel(const ExactLayerKernel&) = delete;
  ExactLayerKernel& operator=(const ExactLayerKernel&) = delete;

  /// Ft(sigma), even in sigma (dimensionless; any finite sigma).
  double kernel(double sigma) const;
  /// dFt/dsigma, odd in sigma.
  double kernel_derivative(double sigma) const;
  /// E* = E/(1 - nu^2) [Pa].
  double effective_modulus() const { return E_star_; }
  /// The layer; for a stack its top layer (E1, nu1, h1).
  const ElasticLayer& layer() const { return layer_; }
  /// The medium: a one-layer stack for an ElasticLayer.
  const LayeredMedium& medium() const { return medium_; }
  const ExactLayerOptions& options() const { return options_; }

  /// Non-adhesive state at contact radius a for `profile`, with error estimates (when
  /// ExactLayerOptions::estimate_error: a second solve with 3/4 of the nodes).
  ExactLayerState solve(const Profile& profile, double a) const;
  /// The same state without an error estimate (one solve).
  NonAdhesiveState state(const Profile& profile, double a) const;

  /// Non-adhesive states at a = a_max j / count, j = 1..count, from one factorisation: the
  /// radii are panel boundaries of one grid, and each smaller radius is the leading block
  /// of the largest (no error estimate). count >= 1.
  std::vector<NonAdhesiveState> sweep(const Profile& profile, double a_max, int count) const;

  /// Non-adhesive contact pressure p(r) [Pa] at radii r in [0, a) for contact radius a:
  /// p(r) = -int_r^a g'(t) / sqrt(t^2 - r^2) dt (g(a) = 0), with g' from the Nystrom
  /// interpolant and tanh-sinh quadrature in s = sqrt(t^2 - r^2). Integrates to P_H to
  /// ~1e-8 (tests).
  std::vector<double> pressure(const Profile& profile, double a,
                               const std::vector<double>& radii) const;

  /// Flat-punch factor P/(2 E* a delta) at a/h (> 0).
  double flat_punch_factor(double a_over_h) const;

 private:
  ElasticLayer layer_;
  LayeredMedium medium_;
  ExactLayerOptions options_;
  double E_star_;
  std::shared_ptr<const detail::LayerKernelFunction> kernel_;  // shared per (nu, base) and Context
};

/// Edge-correction length of a thin layer in units of h: the exact layer behaves like a
/// Winkler foundation at the effective contact radius a + beta h (docs/theory.md s.6). Fitted
/// once from the exact solver, as the beta at which a paraboloid's Winkler approach
/// matches the exact one at a/h = 50 (~0.1 s). nu in (-1, 0.5).
/// Measured: 0.183 (bonded, nu = 0), 0.124 (0.3), -0.098 (0.4), -0.505 (0.45), 0.177
/// (frictionless, any nu).
double edge_correction_beta(const ElasticLayer& layer);

/// ContactModel "edge_corrected" (beyond the paper): Winkler's P_H, delta_H, S and S'
/// evaluated at a + beta h, with beta from edge_correction_beta. This is consistent
/// (dP_H/d delta_H = S) and costs as much per point as Winkler. Its error against the
/// exact layer (docs/models.md) is 0.13 % at a/h = 5 and 0.02 % at a/h = 10 (bonded, nu <= 0.3,
/// or frictionless), against Winkler's 13 % and 7 %. Requires a + beta h > 0.
ContactModelPtr make_edge_corrected(ProfilePtr profile, const ElasticLayer& layer);

/// ContactModel "exact": the exact layer for a profile. The shared kernel is fetched in
/// the constructor; state(a) costs one Nystrom solve pair (ms to s, docs/benchmarks.md).
ContactModelPtr make_exact_layer(ProfilePtr profile, const ElasticLayer& layer,
                                 const ExactLayerOptions& options = {});
/// ContactModel "exact" for a stack of layers (E* and h of its top layer; power laws from
/// per-stack tables in a/h1).
ContactModelPtr make_exact_layer(ProfilePtr profile, const LayeredMedium& medium,
                                 const ExactLayerOptions& options = {});

}  // namespace layerjkr
