// layerjkr: how adhesion acts - the adhesive law that turns a medium's non-adhesive contact
// into an adhesive curve, chosen in a scene by its "adhesion" key.
//
//   JKR (default, jkr.hpp):  adhesion at the contact edge only - the explicit transform (19).
//   DMT:                     adhesion outside the contact, not deforming it. Without sigma0 the
//                            classical limit P = P_H(a) - 2 pi w R, delta = delta_H(a), R = 1/f''(0)
//                            the tip's radius, on every medium; with sigma0 a Dugdale law over the
//                            gap of the non-adhesive state (half-space, exact layer and stacks).
//   Maugis-Dugdale:          a constant tension sigma0 over a < r < c, c where the gap reaches
//                            h0 = w / sigma0 (maugis_dugdale.hpp): the transition between the two,
//                            JKR as lambda -> infinity and DMT as lambda -> 0.
//
//   AdhesionSpec adhesion;                    // scene.hpp reads it from {"adhesion": {...}}
//   adhesion.model = AdhesionModel::maugis_dugdale;
//   adhesion.sigma0 = 20e6;                   // [Pa]
//   AdhesiveLawPtr law = make_adhesive_law(model, spec, w, adhesion);
//   AdhesiveSolution solution(law);           // contact.hpp: pull-off, lookups, curves
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/jkr.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// Rate-dependent adhesion of the JKR edge crack (Maugis & Barquins 1978): while the contact
/// recedes at speed v = -da/dt the energy release rate is G = w0 (1 + (v / v_star)^n), w0 the
/// scene's w (the work of adhesion at vanishing speed), so v = v_star (G/w0 - 1)^(1/n) where
/// G > w0; a contact that G would close (G < w0) does not advance on the retract (it is held: the
/// approach is at equilibrium, G = w0). kinetics.hpp follows the retract it gives.
struct CrackKinetics {
  double v_star = 0.0;  ///< [m/s] > 0, finite: the speed at which G = 2 w0
  double n = 0.0;       ///< the exponent, > 0 and at most 10 (0.6 for Maugis-Barquins' polyurethane)
  /// Throws DomainError naming the first invalid field.
  void validate() const;
  /// -da/dt [m/s] at energy release rate G [J/m^2] for w0 > 0: 0 where G <= w0.
  double crack_speed(double G, double w0) const;
  /// One line: "maugis_barquins(v_star = 1e-06 m/s, n = 0.6)".
  std::string describe() const;
};

/// The adhesion model of a scene and its Dugdale stress.
struct AdhesionSpec {
  AdhesionModel model = AdhesionModel::jkr;
  /// Dugdale stress sigma0 [Pa], > 0: the constant tension of the adhesive zone, whose range
  /// is h0 = w / sigma0.
  std::optional<double> sigma0;
  /// Instead of sigma0: the equilibrium spacing z0 [m] > 0 of a Lennard-Jones law, whose
  /// maximum stress sigma0 = 16 w / (9 sqrt(3) z0) the Dugdale law takes (Johnson & Greenwood
  /// 1997). At most one of sigma0 and z0.
  std::optional<double> z0;
  /// The spacing the check on a JKR answer assumes when neither is given: 0.3 nm, an
  /// interatomic distance (Tabor 1977 and Johnson & Greenwood 1997 take 0.3-0.5 nm; a
  /// larger z0 lowers sigma0 and lambda and moves the contact towards DMT).
  static constexpr double kAssumedSpacing = 0.3e-9;
  /// JKR only: the edge crack's kinetics (rate-dependent adhesion); none: at equilibrium, G = w.
  std::optional<CrackKinetics> kinetics;

  /// Throws DomainError naming the first invalid field.
  void validate() const;
  /// The Dugdale stress [Pa] for work of adhesion w [J/m^2] > 0: sigma0, or that of z0, or
  /// that of kAssumedSpacing.
  double dugdale_stress(double w) const;
  /// True when dugdale_stress comes from kAssumedSpacing (neither sigma0 nor z0 given).
  bool stress_assumed() const { return !sigma0 && !z0; }
};

/// The classical DMT state of a non-adhesive state: P = P_H - 2 pi w R, delta = delta_H, c
/// infinite (the long-range limit). R [m] > 0 is the tip's radius of curvature, w >= 0.
AdhesiveState dmt_transform(const NonAdhesiveState& hertz, double w, double R);

/// An adhesive law: the adhesive state of one contact at each contact radius. Implementations
/// are immutable and thread-safe (every law in this library).
class AdhesiveLaw {
 public:
  virtual ~AdhesiveLaw() = default;
  /// The adhesive state at contact radius a [m] in (min_radius, max_radius] of contact(); a = 0
  /// as well where has_zero_radius_state().
  virtual AdhesiveState at(double a) const = 0;
  /// States at many radii (the default calls at(); laws sharing work across radii override it).
  virtual std::vector<AdhesiveState> curve(const std::vector<double>& radii) const;
  virtual AdhesionModel model() const = 0;
  /// True where a = 0 is a state of the law: the adhesive zone pulls with no contact (DMT,
  /// Maugis-Dugdale), so load-controlled pull-off may happen there.
  virtual bool has_zero_radius_state() const { return false; }
  /// The non-adhesive contact the law starts from (shared, never null).
  const ContactModelPtr& contact() const { return contact_; }
  double w() const { return w_; }
  /// e.g. "exact", "dmt on half_space", "maugis_dugdale (sigma0 = 2e+07 Pa) on exact".
  virtual std::string name() const = 0;
  /// The most radii one curve answer (solve_curve) takes with this law, and what one radius
  /// costs, said in its refusal. A law solved per state on a layer or a stack costs 5-13 ms a
  /// radius, so that a small input (100 000 radii) would buy a quarter of an hour; the others
  /// have no limit of their own (0 means none).
  virtual std::size_t max_curve_radii() const { return 0; }
  virtual std::string radius_cost() const { return std::string(); }

 protected:
  AdhesiveLaw(ContactModelPtr contact, double w);

 private:
  ContactModelPtr contact_;
  double w_;
};
using AdhesiveLawPtr = std::shared_ptr<const AdhesiveLaw>;

/// max_curve_radii() of a Dugdale law solved on a layer or stack: ~26 s at 13 ms a radius.
inline constexpr std::size_t kMaxDugdaleLayerRadii = 2000;

/// The JKR law of a contact model: jkr_transform of its states. w [J/m^2] >= 0.
AdhesiveLawPtr make_jkr_law(ContactModelPtr model, double w);

/// The law `adhesion` asks for on `model`, which was built from `spec` (model_spec.hpp; the
/// Dugdale laws solve their medium from it). w [J/m^2] >= 0. Throws InputError when the
/// combination is not offered: classical DMT needs a profile with a tip radius (f''(0) > 0);
/// Maugis-Dugdale and the Dugdale DMT need a model that solves its medium exactly (half_space,
/// or exact for a layer or a stack) and a profile.
AdhesiveLawPtr make_adhesive_law(ContactModelPtr model, const ModelSpec& spec, double w,
                                 const AdhesionSpec& adhesion);

}  // namespace layerjkr
