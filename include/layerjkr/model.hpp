// layerjkr: elastic media and the non-adhesive (Hertz-type) contact models.
//
// A ContactModel maps a contact radius a [m] to the non-adhesive state
//   P_H(a) [N], delta_H(a) [m], S(a) = dP_H/d delta_H [N/m], S'(a) = dS/da [N/m^2].
// S is also the flat-punch stiffness at radius a (paper, section 3), which is
// what the JKR transform (jkr.hpp) needs.
//
// Models, their parameters and validity (docs/models.md):
//   Winkler (K [N/m^3])            eq. (41): leading order of a thin bonded layer, a >> h.
//   two-term (K, G [N/m], any sign) eqs. (43)-(45) with the corrected force (docs/erratum.md):
//                                  P_H = pi K [a^2 f - 2M] + pi G a [f' - a f''],  S = pi K a^2.
//   full foundation (K, G > 0)     Pasternak (or Filonenko-Borodich with G -> T) on the whole
//                                  plane with the decaying exterior solution (docs/theory.md s.3).
//   half-space (E, nu)             Galin / Sneddon, any profile; S = 2 E* a.
//   ODE route                      the same foundations with P_H obtained by integrating
//                                  dP_H/da = S(a) d delta_H/da (independent of the moment M).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "layerjkr/profile.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

class Context;  // layerjkr/context.hpp

/// Non-adhesive state at one contact radius (SI units).
struct NonAdhesiveState {
  double a = 0.0;        ///< contact radius [m]
  double P_H = 0.0;      ///< force [N]
  double delta_H = 0.0;  ///< approach (indentation) [m]
  double S = 0.0;        ///< contact stiffness dP_H/d delta_H [N/m]
  double dS_da = 0.0;    ///< dS/da [N/m^2]
};

/// A medium plus a solution method for a given indenter profile.
class ContactModel {
 public:
  explicit ContactModel(ProfilePtr profile);
  /// A model built from data (discrete.hpp) has no indenter profile; it must override
  /// max_radius() and typical_radius(), and profile() throws.
  struct FromData {};
  explicit ContactModel(FromData);
  virtual ~ContactModel() = default;

  /// Non-adhesive state at contact radius a (0 < a, a admissible for the profile).
  virtual NonAdhesiveState state(double a) const = 0;

  /// States at several radii, as state(a) for each. Models that can share work across
  /// radii override it (the exact layer: an evenly spaced grid from one factorisation).
  virtual std::vector<NonAdhesiveState> states(const std::vector<double>& radii) const;

  /// Short model name, e.g. "winkler", "two_term", "full_foundation", "half_space".
  virtual std::string name() const = 0;

  /// Contact radii must exceed this [m] (0 for every model but edge_corrected with
  /// beta < 0); searches for critical points and roots stay above it.
  virtual double min_radius() const { return 0.0; }

  /// Largest admissible contact radius [m]: the profile's, or less where the model is
  /// bounded (exact layer: ExactLayerOptions::max_a_over_h * h).
  virtual double max_radius() const;

  /// A typical contact radius [m], used only to seed root and minimum searches (never
  /// changes a result): the profile's length scale, or for the exact layer the smaller of
  /// that and h, so searches start where its states are cheap.
  virtual double typical_radius() const;

  /// Estimated relative error of this model's own numerics at contact radius a [m] - not of
  /// the model against the exact layer (model_error.hpp). 1e-12 for the closed forms and
  /// quadratures, which the tests hold to that level; the exact layer solves once more with
  /// 3/4 of the nodes and returns the difference (and at least its tables' 1e-9).
  virtual double numerical_error(double a) const;

  /// The indenter profile; throws Error for a model built from data.
  const Profile& profile() const;
  bool has_profile() const { return profile_ != nullptr; }
  const ProfilePtr& profile_ptr() const { return profile_; }

 private:
  ProfilePtr profile_;
};

using ContactModelPtr = std::shared_ptr<const ContactModel>;

/// Winkler foundation p = K w; K [N/m^3] > 0. Cost: one profile evaluation per point.
ContactModelPtr make_winkler(ProfilePtr profile, double K);

/// Two-term asymptotic thin layer / asymptotic Pasternak model p = K w - G lap w inside
/// the contact with p(a) = 0. K > 0 [N/m^3]; G [N/m] finite, any sign (G < 0 for a
/// bonded layer with nu > 1/4). G = 0 reduces exactly to Winkler.
ContactModelPtr make_two_term(ProfilePtr profile, double K, double G);

/// Full Pasternak foundation (or Filonenko-Borodich with G = tension T) with the
/// decaying exterior solution w = c K0(lam r)/K0(lam a), lam = sqrt(K/G). K > 0, G > 0;
/// G <= 0 throws (use make_two_term, the asymptotic model, instead).
ContactModelPtr make_full_foundation(ProfilePtr profile, double K, double G);

/// Elastic half-space with plane-strain modulus E* = E/(1 - nu^2) for any profile
/// (Sneddon's form of Galin's eq. (21)); closed forms for paraboloid (Hertz), sphere,
/// cone and power law, adaptive quadrature otherwise. E > 0 [Pa], nu in (-1, 0.5].
ContactModelPtr make_half_space(ProfilePtr profile, double E, double nu);

/// The ODE route: delta_H from the local edge condition, S from the flat punch, and
/// P_H(a) = int_0^a S(s) delta_H'(s) ds by GSL's adaptive QAGP (split at profile kinks),
/// relative tolerance `rel_tol`. Independent of the closed-form moment; used to verify
/// the closed forms and for profiles whose moment is expensive. kind = full needs G > 0.
ContactModelPtr make_ode_foundation(ProfilePtr profile, double K, double G, FoundationKind kind,
                                    double rel_tol = 1e-12);

/// An isotropic elastic layer of thickness h on a rigid base.
struct ElasticLayer {
  double E = 0.0;   ///< Young's modulus [Pa], > 0
  double nu = 0.0;  ///< Poisson's ratio, in (-1, 0.5)
  double h = 0.0;   ///< thickness [m], > 0
  Base base = Base::bonded;
};

/// Thin incompressible layer bonded to a rigid base (nu = 0.5 exactly): the lubrication-type
/// leading-order law w = -(h^3 / (3 mu)) lap p with p(a) = 0 (docs/theory.md s.2). For any
/// profile, with M(a) = int_0^a f r dr: delta_H = 2 M(a)/a^2 (no pressure gradient at the
/// edge), P_H = (pi E / (4 h^3)) int_0^a f r (2 r^2 - a^2) dr, S = pi E a^4 / (8 h^3),
/// S' = pi E a^3 / (2 h^3); a paraboloid gives a^2 = 4 R delta_H and
/// P_H = pi mu a^6 / (32 R h^3) = 2 pi mu R^2 delta^3 / h^3. It lies below the exact layer by
/// O(h/a): 8.7 h/a in P_H, 5.8 h/a in S, 2.9 h/a in delta_H (docs/models.md). Closed forms
/// for power laws, else tanh-sinh quadrature (1e-13). E > 0 [Pa], h > 0 [m]; nu other than
/// 0.5 or a frictionless base throw.
ContactModelPtr make_incompressible_layer(ProfilePtr profile, const ElasticLayer& layer);

/// The two-term compliance expansion of a bonded layer, w = eps p - D lap p
/// (docs/theory.md s.2a): finite for every nu in (-1, 0.5], unlike K = 1/eps and
/// G = -D K^2, which blow up at nu = 1/2.
///   eps = h (1+nu)(1-2nu) / [E (1-nu)]               [m^3/N]
///   D   = h^3 nu (4nu-1)(1+nu) / [3 E (1-nu)^2]     [m^5/N]  (nu = 1/2: h^3/E)
struct UniformLayerConstants {
  double eps = 0.0;
  double D = 0.0;
};
/// Throws DomainError for E <= 0, h <= 0, nu outside (-1, 0.5] or a frictionless base.
UniformLayerConstants uniform_layer_constants(const ElasticLayer& layer);

/// Thin bonded layer, uniformly valid in nu up to 1/2 (`"model": "uniform"`,
/// docs/theory.md s.2a). Where D > 0 (nu > 1/4 or nu < 0) the pressure form
/// eps p - D lap p = w with p(a) = 0 (and p'(a) = 0 for the non-adhesive state); with
/// k = sqrt(eps/D), x = k a:
///   delta_H = int_0^a f I0(k r) r dr / int_0^a I0(k r) r dr,
///   S = pi a^4 phi(x) / D with phi = (1 - 2 I1/(x I0)) / x^2,  S' = 2 pi a^3 (I1/(x I0))^2 / D,
/// which is the incompressible law at nu = 1/2 and Winkler as D -> 0. Where D < 0
/// (0 < nu < 1/4) the pressure form is ill-posed and the same two terms are taken in stiffness
/// form, the full Pasternak model with K = 1/eps, G = -D/eps^2; D = 0 is Winkler.
/// With edge_correction (the default) the state is that law's at a + beta h, beta from
/// uniform_layer_beta. Measured against the exact layer (docs/models.md), worst of P_H,
/// delta_H and S over paraboloid, sphere, cone and r^4: without the correction O(h/a) with a
/// coefficient up to 8.6 (nu = 0.5); with it at most 6 (h/a)^2 for nu <= 0.49 (0.7 % at
/// a/h = 10 for nu = 0.45), and 0.5 h/a at nu = 0.5. Tanh-sinh quadrature (1e-13) for every
/// profile, 6-50 us a state; the first use of a nu costs one exact solve (~20 ms).
/// beta comes from uniform_layer_beta(layer, context).
ContactModelPtr make_uniform_layer(ProfilePtr profile, const ElasticLayer& layer,
                                   bool edge_correction = true,
                                   const std::shared_ptr<Context>& context = nullptr);

/// Edge-correction length of the uniform model in units of h, fitted once per nu and cached
/// in `context` (null: Context::global(), which make_contact_model uses), with the exact
/// kernel from the same Context, so that a paraboloid's approach matches the exact layer's
/// at a/h = 50. Measured: 0.18 (nu = 0), 0.39 (0.3), 0.93 (0.45), 1.23 (0.49), 1.39 (0.5).
double uniform_layer_beta(const ElasticLayer& layer, const std::shared_ptr<Context>& context = nullptr);

/// Foundation constants of a thin layer, with warnings about validity.
struct ThinLayerConstants {
  double K = 0.0;  ///< [N/m^3]
  double G = 0.0;  ///< [N/m]
  std::vector<std::string> warnings;
};

/// Thin-layer constants (docs/theory.md s.2):
///   bonded:       K = E(1-nu)/[h(1+nu)(1-2nu)],  G = h E nu(1-4nu)/[3(1+nu)(1-2nu)^2]
///   frictionless: K = E/[h(1-nu^2)],             G = 0 (no h^2 term)
/// Throws DomainError for E <= 0, h <= 0, nu <= -1 or nu >= 0.5. For a bonded layer
/// with nu > 0.45 a warning says that the compressible expansion is non-uniform and
/// needs a/h well above sqrt(nu(4nu-1)/(3(1-2nu)(1-nu))).
ThinLayerConstants thin_layer_constants(const ElasticLayer& layer);

/// Plane-strain modulus E* = E/(1-nu^2) [Pa]; E > 0, nu in (-1, 0.5].
double effective_modulus(double E, double nu);

}  // namespace layerjkr
