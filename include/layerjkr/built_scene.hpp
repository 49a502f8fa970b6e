// layerjkr: a scene turned into its contact model, with the judge of that model's answers.
//
// resolve_model (scene.hpp) says which model a scene means; this builds it for the radii an
// answer needs: model "auto" is chosen there (model_choice.hpp), and every model gets the
// reference it is judged against (model_error.hpp). The answers (answer.hpp) and the fit
// (fit.hpp) build their models here.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/model.hpp"
#include "layerjkr/model_error.hpp"
#include "layerjkr/scene.hpp"
#include "layerjkr/types.hpp"

namespace layerjkr {

/// What model "auto" chose, and how well the choice was judged to do.
struct AutoChoice {
  ModelKind model = ModelKind::exact;
  double estimated_error = 0.0;  ///< the chosen model's worst estimate where it was judged
  double tolerance = 0.0;        ///< the scene's target
  std::string judged_at;         ///< e.g. "over the curve's radii"
  /// One line: "auto chose model 'uniform' (estimated error 0.003 over the curve's radii)".
  std::string brief_report() const;
};

/// The scene's contact model, built, with what it was resolved from.
struct BuiltScene {
  ContactModelPtr model;
  /// The model `model` approximates, which its answers are judged against; null where
  /// `model` solves its medium exactly (ResolvedModel::reference).
  ContactModelPtr reference;
  ResolvedModel resolved;             ///< K, G, E*, the validity warnings
  std::optional<AutoChoice> choice;   ///< model "auto" only
};

/// Builds the contact model of a scene. Model "auto" chooses the cheapest model within the
/// scene's tolerance at contact radii a_min * 2^k, k = 0..4 (a_min [m] required > 0 for
/// "auto", ignored otherwise): every reduced model's error falls as a/h grows, so a range
/// starting at a_min is judged by its first octaves. `with_reference` false skips building
/// the reference where nothing will be judged (a fit); "auto" builds it anyway to choose.
/// Invalid constants throw InputError naming the scene's medium.
BuiltScene build_scene(const Scene& scene, double a_min = 0.0, bool with_reference = true);

/// The same, with "auto" judged at exactly these contact radii [m] (a curve's).
BuiltScene build_scene_for_radii(const Scene& scene, const std::vector<double>& radii);

/// The same, with "auto" judged by what a summary reports: the pull-off force and the
/// zero-load radius, against the exact layer's.
BuiltScene build_scene_for_summary(const Scene& scene);

/// The judge of a built scene's answers: its model against its reference, for the scene's w.
ModelErrorEstimator error_estimator(const Scene& scene, const BuiltScene& built);

}  // namespace layerjkr
