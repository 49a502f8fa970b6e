// layerjkr: automatic model choice for a thin layer ("model": "auto").
//
// Every candidate is judged a posteriori on the scene itself, against the exact layer for
// the same profile (model_error.hpp), so the choice holds for any profile - sphere, cone,
// power law, table, callable - and any nu up to 1/2. The candidates, cheapest per state first
// (bench_models, docs/benchmarks.md): winkler, two_term, edge_corrected, full_foundation,
// incompressible (nu = 1/2), uniform (bonded), and the exact layer when none is within the
// tolerance. Validated on 200 random scenes (tests/models/test_model_choice.cpp): the estimate
// bounds the error against a finer exact solution in every scene, and the choice is the
// cheapest model within tolerance in every scene as well.
#pragma once

#include <string>
#include <vector>

#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model.hpp"
#include "layerjkr/model_spec.hpp"

namespace layerjkr {

/// The reduced models "auto" considers for `layer`, cheapest per state first (the exact layer,
/// the fallback, is not listed). Models that do not apply are left out: two_term where G = 0,
/// full_foundation where G <= 0, the compressible ones at nu = 1/2, incompressible for
/// nu < 1/2, uniform on a frictionless base.
std::vector<ModelKind> layer_model_candidates(const ElasticLayer& layer);

/// The spec of a layer model `kind` (thin-layer constants filled in where it needs them).
ModelSpec layer_model_spec(ModelKind kind, const ElasticLayer& layer);

struct ModelChoice {
  ModelKind model = ModelKind::exact;  ///< one of layer_model_candidates, or exact
  double estimated_error = 0.0;  ///< the chosen model's worst estimate where it was judged
  ContactModelPtr contact_model;
  ContactModelPtr reference;     ///< the exact layer it was judged by (null if it is the choice)
};

/// Cheapest model whose estimated error (ModelErrorEstimator::at, work of adhesion w [J/m^2])
/// at every radius in `radii` [m] (non-empty, > 0) is within `tolerance` (in (0, 1)). With more
/// than 24 radii the estimate comes from 24 anchors spanning them.
ModelChoice choose_layer_model(const ProfilePtr& profile, const ElasticLayer& layer, double w, double tolerance,
                               const std::vector<double>& radii);

/// Cheapest model whose summary (pull-off force, zero-load radius; ModelErrorEstimator::summary)
/// is within `tolerance` of the exact layer's. Costs one exact summary plus one summary per
/// candidate tried.
ModelChoice choose_layer_model_for_summary(const ProfilePtr& profile, const ElasticLayer& layer, double w,
                                           double tolerance);

/// A stack's candidates for model "auto", cheapest first: on a rigid base its thin-stack laws
/// (winkler with K = 1/C(0); two_term on a bonded base; incompressible alone for a bonded
/// stack of incompressible layers), none on a half-space (layered_medium.hpp, theory.md s.4a).
std::vector<ModelKind> stack_model_candidates(const LayeredMedium& medium);

/// The spec of `kind` (exact, winkler, two_term or incompressible) for a stack.
ModelSpec stack_model_spec(ModelKind kind, const LayeredMedium& medium);

/// choose_layer_model and choose_layer_model_for_summary for a stack, judged against the exact
/// stack.
ModelChoice choose_stack_model(const ProfilePtr& profile, const LayeredMedium& medium, double w, double tolerance,
                               const std::vector<double>& radii);
ModelChoice choose_stack_model_for_summary(const ProfilePtr& profile, const LayeredMedium& medium, double w,
                                           double tolerance);

}  // namespace layerjkr
