// layerjkr: a stack of perfectly bonded isotropic elastic layers (a coating on a substrate),
// on a rigid base (bonded or frictionless) or bonded to an elastic half-space; its top
// surface is frictionless (docs/theory.md s.4a).
//
// The surface deflection under an axisymmetric pressure with Hankel transform p^(k) is
//   w(r) = int_0^inf (2 L(k h1) / (E1* k)) p^(k) J0(k r) k dk,
// E1* = E1/(1 - nu1^2) and h1 of the TOP layer: L is the stack's compliance relative to the
// half-space of its top layer (L = 1 for that half-space, L(u) of theory.md s.4 for N = 1 on
// a rigid base). The exact solver (exact_layer.hpp) takes a stack in place of one layer.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

#include "layerjkr/model.hpp"

namespace layerjkr {

/// One layer of a stack.
struct StackLayer {
  double E = 0.0;   ///< Young's modulus [Pa], > 0
  double nu = 0.0;  ///< Poisson's ratio, in (-1, 0.5] (0.5: incompressible)
  double h = 0.0;   ///< thickness [m], > 0
};

/// An elastic half-space under a stack.
struct Substrate {
  double E = 0.0;   ///< Young's modulus [Pa], > 0
  double nu = 0.0;  ///< Poisson's ratio, in (-1, 0.5]
};

/// The most layers a stack may have: its kernel's set-up grows with them (25 ms a layer,
/// measured: 300 layers took 7.6 s before the first state), so a small scene of thousands of
/// layers could buy minutes. Real coatings, primers and cells have a few.
inline constexpr std::size_t kMaxStackLayers = 64;

/// N >= 1 layers (at most kMaxStackLayers), top first, on a rigid `base` or, when `substrate` is
/// set, bonded to that elastic half-space (then `base` is unused).
struct LayeredMedium {
  std::vector<StackLayer> layers;
  Base base = Base::bonded;
  std::optional<Substrate> substrate;

  /// The one-layer stack of `layer` (on its base).
  static LayeredMedium single(const ElasticLayer& layer);
  /// The top layer as an ElasticLayer (E1, nu1, h1; base: the stack's, bonded on a substrate).
  ElasticLayer top() const;
  /// True for one layer on a rigid base: exactly an ElasticLayer.
  bool is_single_layer() const { return layers.size() == 1 && !substrate; }
  /// Throws DomainError naming the first invalid value, e.g. "layers[1].h" or "substrate.nu",
  /// with its valid range; at least one layer.
  void validate(const char* function) const;
};

/// The thin-stack (k H -> 0) expansion of a stack on a rigid base: the surface compliance
/// C(k) = 2 L(k h1)/(E1* k) = eps + D k^2 + O(k^4) on a bonded base, i.e. the two-term law
/// w = eps p - D lap p (theory.md s.4a), and C(0) on a frictionless base. With depth z,
/// M = lambda + 2 mu (infinite at nu = 1/2), beta = nu/(1 - nu):
///   eps = sum_i h_i/M_i  (springs in series; an incompressible layer drops out)
///   D   = 2 int_0^H B(z) [beta(z) a(z) - b(z)] dz,  a = int_z^H dz'/mu, b = int_z^H dz'/M,
///         B = int_0^z beta dz'  (all layers incompressible: D = int_0^H z^2/mu dz)
///   frictionless C(0) = eps + (sum_i h_i beta_i)^2 / sum_i (2 mu_i h_i/(1 - nu_i))
/// They need a >> H, the whole stack's thickness, not just a >> h1.
struct ThinStackConstants {
  double eps = 0.0;           ///< bonded base: C(0) [m^3/N]
  double D = 0.0;             ///< bonded base: the k^2 coefficient [m^5/N]
  double frictionless = 0.0;  ///< frictionless base: C(0) [m^3/N]
  double K = 0.0;             ///< Winkler modulus 1/C(0) of the stack's own base [N/m^3] (inf if C(0) = 0)
  double G = 0.0;             ///< bonded base: -D/eps^2 [N/m], the two-term law's G (NaN if eps = 0)
};

/// The thin-stack constants of a stack on a rigid base; a substrate throws DomainError (on a
/// half-space no local law exists: theory.md s.4a).
ThinStackConstants thin_stack_constants(const LayeredMedium& medium);

/// A stack of incompressible layers (every nu = 1/2) bonded to a rigid base obeys, thin, the
/// lubrication law w = -J lap p with J = D = int_0^H z^2/mu dz: the law of one incompressible
/// layer (make_incompressible_layer, which depends on h^3/E only) of thickness H and modulus
/// E = H^3/J. Returns that layer; DomainError for any other stack.
ElasticLayer equivalent_incompressible_layer(const LayeredMedium& medium);

/// L(u) of the stack at u = k h1 >= 0 (see above): the stable bottom-up recursion of
/// docs/theory.md s.4a, accurate to a few ulps relative for every u >= 1e-100 (no growing
/// exponentials); below 1e-100, its limit L(0) (0 on a rigid base, E1*/Es* on a substrate).
double stack_compliance_ratio(const LayeredMedium& medium, double u);

}  // namespace layerjkr
