// layerjkr: adhesion on a relaxing medium - the Maugis-Dugdale contact of an axisymmetric indenter
// on a linear viscoelastic half-space, followed in time under fixed grips.
//
// The adhesive stress is a constant tension sigma0 [Pa] over the annulus a < r < c outside the
// contact, acting until the gap reaches h0 = w / sigma0 (maugis_dugdale.hpp's law). The medium's
// modulus relaxes as E(t) = E psi(t) at constant nu (viscoelastic.hpp). In the Copson variables of
// docs/theory.md s.8 the half-space is local in x: at every x,
//
//   g(x, t) = (E*/pi) int psi(t - s) d_s D(x, s),
//
// with D = delta - F(x) inside the contact, g the Dugdale annulus's Copson function in the adhesive
// zone and g = 0 beyond it. So each x keeps its own history, and at each step the contact and
// adhesive-zone radii (a, c) are where g is continuous at a (the contact's edge bears a bounded
// pressure) and the gap at c is h0. Nothing else is assumed: the crack's rate dependence, the
// hysteresis between approach and retract and the pull-off's rise with speed all come out of the
// stepping (docs/theory.md s.8a derives it and its limits). With psi = 1 every step is Maugis'
// elastic solution; a history much faster than the law's times is the elastic contact at the
// instantaneous modulus, one much slower that at the relaxed modulus.
//
//   RelaxingDugdaleOptions o;                       // 4 001 grid points
//   auto r = relaxing_dugdale_response(profile, E_star, law, w, sigma0, t, delta, o);
//   r.P[i];                                         // force [N] at t[i]; 0 once the contact is lost
#pragma once

#include <cstddef>
#include <vector>

#include "layerjkr/profile.hpp"
#include "layerjkr/viscoelastic.hpp"

namespace layerjkr {

struct RelaxingDugdaleOptions {
  /// Points of the uniform grid in x on [0, extent] that carries each x's history (>= 201). The
  /// adhesive zone must span several: the error falls as the square of the spacing (measured in
  /// tests/time/test_viscoelastic_adhesion.cpp).
  int grid_points = 4001;
  /// The grid's extent [m] (> 0), or 0: 1.5 times the adhesive zone's radius of the elastic
  /// contact at the relaxed modulus at the deepest indentation (the largest the zone grows on a
  /// history that approaches once). A zone that outgrows the grid is refused.
  double extent = 0.0;
  /// Equal sub-steps per sample interval, delta linear in time within it (>= 1), or 0: halved
  /// until the force of two successive levels differs by at most 3 tolerance times the largest
  /// force (the error is second order in the step; the finer level's, a third of the difference, is
  /// reported) and both lose the contact at the same sample, up to max_substeps. The step must
  /// resolve the law's times and the time the crack takes to cross its adhesive zone: at one step
  /// per sample a curve's lowest force was 17 % off for a law relaxing within one sample.
  int substeps = 0;
  double tolerance = 1e-3;  ///< in (0, 1): of the largest |force|
  int max_substeps = 256;   ///< >= 2
  /// 0: fixed grips (delta is the tip's indentation). > 0 [N/m]: a cantilever of this stiffness;
  /// delta is then its base's position z and the tip sits at z - P/k (RelaxingDugdaleResponse::tip),
  /// found at each step on the contact's branch; the lever lets go where none balances it (past
  /// dP/d delta = -k). The history snaps in with the lever unbent at delta[0] (simulate snaps in at
  /// zero load, where it is).
  double cantilever_stiffness = 0.0;
  /// Throws DomainError naming the first invalid field, its value and the valid range.
  void validate() const;
};

struct RelaxingDugdaleResponse {
  /// Per sample: the force [N] (negative = tensile), the contact radius a [m] and the adhesive
  /// zone's outer radius c [m]; all 0 once the contact is lost.
  std::vector<double> P, a, c;
  /// The tip's indentation [m] per sample: delta itself under fixed grips; under a cantilever
  /// z - P/k in contact and the base's z once the lever has let go.
  std::vector<double> tip;
  /// The first sample after the contact was lost (the fixed-grips branch ended or a fell below
  /// 1e-4 of its largest value); P.size() when it never is.
  std::size_t separated_at = 0;
  double extent = 0.0;  ///< the grid's extent [m]
  int grid_points = 0;
  int substeps = 0;          ///< steps per sample interval used
  /// With automatic sub-steps: the estimated largest error of P [N] (a third of the difference
  /// from the level with half the sub-steps), and whether it met the tolerance; with fixed
  /// sub-steps, 0 and true (not estimated).
  double force_error = 0.0;
  bool converged = true;
};

/// The force of `profile` pressed by the indentation history delta[i] [m] (positive into the
/// medium) at times t[i] [s] (strictly increasing) into a half-space of plane-strain modulus E_star
/// [Pa] (instantaneous: E*(t) = E_star psi(t)) with work of adhesion w [J/m^2] and Dugdale stress
/// sigma0 [Pa]. The history starts with the contact snapping in at delta[0]: the instantaneous
/// elastic Maugis-Dugdale contact there (its largest radius): simulate and the fit snap it in at
/// dugdale_zero_load_indentation at the instantaneous modulus. The law must have psi(0+) = 1
/// (elastic, Prony, fractional); a power law's infinite instantaneous modulus cannot snap in and
/// is refused. Once lost, the contact is not formed again: a history that comes back afterwards
/// by more than 2 % of its span (delta's largest value minus delta[0]) is refused (less is noise).
/// Throws DomainError for invalid values (named, with the valid range), InputError for vectors of
/// different lengths, fewer than 2 samples, times that do not increase, no contact at delta[0] or a
/// re-approach; NumericalError when the adhesive zone outgrows the grid.
RelaxingDugdaleResponse relaxing_dugdale_response(const Profile& profile, double E_star, const RelaxationLaw& law,
                                                  double w, double sigma0, const std::vector<double>& t,
                                                  const std::vector<double>& delta,
                                                  const RelaxingDugdaleOptions& options = {});

/// The indentation [m] at which the elastic Maugis-Dugdale contact of `profile` (its largest
/// radius) on a half-space of plane-strain modulus E_star [Pa], with w [J/m^2] and sigma0 [Pa],
/// carries no load: Maugis' zero-load point (for a paraboloid, maugis_dugdale_half_space's to the
/// root solver's 48 bits). Throws DomainError for a value that is not finite and > 0.
double dugdale_zero_load_indentation(const Profile& profile, double E_star, double w, double sigma0);

}  // namespace layerjkr
