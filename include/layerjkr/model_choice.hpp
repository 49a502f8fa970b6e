// layerjkr: automatic model choice for a thin layer ("model": "auto").
//
// The error of every asymptotic model against the exact layer was measured once
// (tools/model_tradeoff.cpp; table in src/models/model_error_table.inc, summary in
// docs/models.md):
// the worst relative error of P_H, delta_H and the pull-off force, per base, nu in
// {0, 0.1, 0.2, 0.25, 0.3, 0.4, 0.45, 0.49} and a/h in {0.5, ..., 100}. The estimate for
// a scene interpolates that table conservatively: the maximum over the bracketing grid
// points in nu and in a/h, and beyond a/h = 100 the O(h/a) law err(100) * 100/(a/h).
// Outside the measured domain (a/h < 0.5, nu < 0, bonded nu >= 0.49) no estimate
// exists and only the exact solver qualifies. The table holds for a paraboloid only:
// for a cone, a sphere or a power law d != 2 the measured errors exceeded it (f ~ r^4:
// up to 5x; the edge error grows with the force exponent), so for any profile that is
// not a paraboloid "auto" chooses the exact solver.
#pragma once

#include <string>

#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"

namespace layerjkr {

/// Estimated worst relative error of an asymptotic model ("winkler", "edge_corrected",
/// "two_term", "full_foundation") for `layer` at contact radius a [m]; +inf where the model does not
/// apply or was not measured. The exact solver's own error (< 1e-7) is not included.
double estimated_model_error(ModelKind model, const ElasticLayer& layer, double a);
/// The same by name; throws DomainError for a name that is not one of the four.
double estimated_model_error(const std::string& model, const ElasticLayer& layer, double a);

struct ModelChoice {
  std::string model;             ///< winkler | edge_corrected | two_term | full_foundation | exact
  double estimated_error = 0.0;  ///< from estimated_model_error (exact: 1e-7, its accuracy bound)
  double reference_radius = 0.0; ///< the contact radius the choice was made for [m]
  ContactModelPtr contact_model;
};

/// Cheapest model (winkler < edge_corrected < two_term < full_foundation < exact) whose estimated error
/// at every contact radius >= a_min [m] is within `tolerance` (in (0, 1)). The error
/// estimates fall with a/h, so the check is made at a_min.
ModelChoice choose_layer_model(ProfilePtr profile, const ElasticLayer& layer, double tolerance,
                               double a_min);

}  // namespace layerjkr
