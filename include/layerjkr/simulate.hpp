// layerjkr: synthetic force curves from a scene - test data with known answers.
//
// The curve follows the same physics the fit assumes (fit.hpp): on approach the contact
// snaps in at zero load and follows the stable branch; on retract it follows the branch
// down to pull-off and is free after it. The adhesion is the scene's (JKR, DMT or
// Maugis-Dugdale: adhesion.hpp). Radii come from the library's own inverse lookups
// (AdhesiveSolution::force_at_delta), not from the fit's Newton solver.
//
// In time (SimulationOptions::speed > 0) the indenter approaches at `speed`, may rest for
// `dwell`, and withdraws at `retract_speed`; every sample has its time. A relaxing medium
// (medium.viscoelastic) answers by Lee-Radok and Ting's rule (viscoelastic.hpp), the indentation
// following the ramp; crack kinetics (adhesion.kinetics) by the retract's ODE (kinetics.hpp) under
// fixed grips or a cantilever, the approach at equilibrium. Both need a speed.
#pragma once

#include <cstdint>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr {

struct SimulationOptions {
  /// The most samples a branch may have, and the most a dwell may add (at the approach's
  /// sampling interval): bounds on memory a typo (--dwell 1e7) could otherwise exhaust.
  static constexpr std::size_t kMaxPointsPerBranch = 100000;
  static constexpr std::size_t kMaxDwellSamples = 1000000;
  /// Speeds [m/s] the curve in time accepts: 1 fm/s to 1 km/s (beyond, the times overflow or
  /// underflow long before any instrument is reached).
  static constexpr double kSpeedRange[2] = {1e-15, 1e3};
  /// The largest force noise [N]: its Gaussian samples (within ~40 sigma) stay finite.
  static constexpr double kMaxNoise = 1e300 / 64.0;

  Branch branch = Branch::all;        ///< approach, retract, or both (approach first)
  std::size_t points_per_branch = 500;  ///< in [2, kMaxPointsPerBranch]
  /// Turning point: the approach at the deepest point [m] relative to first contact
  /// (> 0). Samples are evenly spaced in delta.
  double max_indentation = 0.0;
  /// Fraction of max_indentation sampled before contact (approach) or after pull-off
  /// (retract), >= 0.
  double free_fraction = 0.5;
  double delta0 = 0.0;  ///< contact-point offset added to every delta [m]
  double P0 = 0.0;      ///< force baseline added to every P [N]
  double noise = 0.0;   ///< standard deviation of Gaussian force noise [N], in [0, kMaxNoise]
  std::uint64_t seed = 1;
  bool with_radius = false;  ///< also return the contact radius (a JKR rig's a column)
  /// The indenter's approach speed [m/s], 0 or in kSpeedRange: > 0 samples the curve in time (t
  /// from 0 at the first sample; needed by a relaxing medium and by crack kinetics); 0: no time.
  double speed = 0.0;
  double retract_speed = 0.0;  ///< [m/s], 0 (the approach's speed) or in kSpeedRange
  /// A rest at the deepest point [s], >= 0 (needs speed): dwell samples (segment 2) at the
  /// approach's sampling interval, at most kMaxDwellSamples of them.
  double dwell = 0.0;
  /// The lever's hydrodynamic drag b [N s/m], finite and >= 0 (needs speed): every force gains
  /// b v, v the base's speed towards the sample - the approach's speed while approaching, minus the
  /// retract's while retracting, 0 at rest - as a lever moving in liquid measures it.
  double drag = 0.0;
  /// What drives a retract with crack kinetics: fixed_grips (the indenter follows the ramp) or
  /// cantilever (the base of a lever of cantilever_stiffness [N/m] follows it; the tip is at
  /// delta = z - P/k). Other scenes' retracts follow the fixed-grips branch to the pull-off.
  RetractControl control = RetractControl::fixed_grips;
  double cantilever_stiffness = 0.0;
  /// Throws DomainError naming the first invalid field.
  void validate() const;
};

/// Samples the adhesive curve of `scene` (model "auto" chooses for radii down to a tenth
/// of the turning point's). Throws DomainError for invalid options, InputError for a relaxing
/// medium or crack kinetics without a speed, and for adhesion (w > 0) on a relaxing medium (not
/// modelled: the bulk's relaxation and the edge's adhesion together), and NumericalError if the
/// scene has no stable branch in the requested range.
CurveData simulate_curve(const Scene& scene, const SimulationOptions& options);

}  // namespace layerjkr
