// layerjkr: scenes - indenter + medium + model + w - read from JSON.
//
//   {"indenter": {"shape": "paraboloid", "R": 0.01},
//    "medium": {"type": "layer", "E": 3e6, "nu": 0.3, "h": 1e-4, "base": "bonded"},
//    "model": "two_term",
//    "w": 0.05}
//
// indenter.shape: paraboloid {R} | sphere {R} | cone {semi_angle_deg} | power_law {B, d}
//                 | table {r: [...], z: [...]}
// medium.type:    winkler {K} | pasternak {K, G} | filonenko_borodich {K, T}
//                 | layer {E, nu, h, base: bonded|frictionless} | half_space {E, nu}
// model:          layer: leading | two_term | edge_corrected | exact (nu may be 0.5) | incompressible
//                 (nu = 0.5, bonded) | uniform (bonded, nu up to 0.5) | auto (needs
//                 "tolerance": the cheapest model whose measured error is within it);  pasternak, filonenko_borodich: asymptotic |
//                 full;  winkler: winkler (default);  half_space: half_space (default)
// solver:         closed_form (default) | ode  (foundation models only)
// w:              work of adhesion [J/m^2], >= 0 (absent = 0)
// All values SI. Unknown keys, wrong types and invalid values throw InputError
// naming the key and the value; nothing is ignored.
#pragma once

#include <string>
#include <vector>

#include "layerjkr/model.hpp"
#include "layerjkr/model_error.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/profile.hpp"

namespace layerjkr {

enum class MediumType { winkler, pasternak, filonenko_borodich, layer, half_space };

/// The scene's "model" key: what the user asked for. Which ones a medium accepts:
/// winkler: winkler; half_space: half_space; layer: leading, two_term, edge_corrected,
/// exact, incompressible, uniform, automatic ("auto"); pasternak and filonenko_borodich: asymptotic, full.
enum class SceneModel { winkler, half_space, leading, two_term, edge_corrected, exact, automatic,
                        asymptotic, full, incompressible, uniform };

/// The scene's spelling of a SceneModel ("auto" for automatic).
const char* to_string(SceneModel model);

/// How a foundation's P_H is computed: closed forms, or the ODE route (model.hpp).
enum class Solver { closed_form, ode };

/// The medium as given in the scene (unused fields are NaN).
struct MediumSpec {
  MediumType type = MediumType::winkler;
  double K = 0.0, G = 0.0, T = 0.0;  ///< foundations [N/m^3], [N/m], [N/m]
  double E = 0.0, nu = 0.0, h = 0.0;  ///< layer / half-space [Pa], [-], [m]
  Base base = Base::bonded;
};

struct Scene {
  ProfilePtr profile;
  MediumSpec medium;
  SceneModel model = SceneModel::winkler;  ///< the scene's model, or the medium's default
  Solver solver = Solver::closed_form;
  double w = 0.0;                     ///< [J/m^2]
  double tolerance = 0.0;             ///< relative error target of model "auto", in (0, 1)
};

/// The scene turned into a contact model, with the constants it used.
struct BuiltScene {
  ContactModelPtr model;
  /// The model `model` approximates, which its errors are estimated against
  /// (model_error.hpp): the exact layer for every thin-layer law, the full foundation for an
  /// asymptotic one with G > 0; null where `model` solves its medium exactly.
  ContactModelPtr reference;
  bool has_foundation_constants = false;
  double K = 0.0;  ///< foundation modulus [N/m^3] (layers: mapped)
  double G = 0.0;  ///< shear modulus or tension [N/m] (layers: mapped)
  bool has_effective_modulus = false;
  double E_star = 0.0;  ///< [Pa], layers and half-space
  std::vector<std::string> warnings;
  /// Model "auto": what was chosen and its estimated error where it was judged.
  bool automatic = false;
  std::string chosen_model;
  double estimated_error = 0.0;
};

/// Parses a scene from JSON text; `source` names it in error messages.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");

/// Reads and parses a scene file. Throws InputError if it cannot be read.
Scene load_scene(const std::string& path);

/// What a scene's model resolves to. Throws DomainError for invalid constants and Error
/// for model "auto", which resolves only for a contact radius (build_scene).
struct ResolvedModel {
  ModelSpec spec;
  /// The medium's foundation constants, as summaries report them (a layer's thin-layer
  /// K and G, also for "leading" and "edge_corrected"; none for "exact").
  bool has_foundation_constants = false;
  double K = 0.0, G = 0.0;
  std::vector<std::string> warnings;  ///< the thin-layer constants' validity warnings
};
ResolvedModel resolve_model(const Scene& scene);

/// Builds the contact model of a parsed scene (through make_contact_model). Model "auto"
/// chooses the cheapest model within the scene's tolerance at contact radii a_min * 2^k,
/// k = 0..4 (a_min [m] required > 0 for "auto", ignored otherwise): every reduced model's
/// error falls as a/h grows, so a range starting at a_min is judged by its first octaves.
BuiltScene build_scene(const Scene& scene, double a_min = 0.0);

/// The same, with "auto" judged at exactly these contact radii [m] (a curve's).
BuiltScene build_scene_for_radii(const Scene& scene, const std::vector<double>& radii);

/// The same, with "auto" judged by what a summary reports: the pull-off force and the
/// zero-load radius, against the exact layer's.
BuiltScene build_scene_for_summary(const Scene& scene);

/// The judge of a built scene's answers: its model against its reference, for the scene's w.
ModelErrorEstimator error_estimator(const Scene& scene, const BuiltScene& built);

}  // namespace layerjkr
