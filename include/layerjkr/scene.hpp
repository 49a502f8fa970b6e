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
// model:          layer: leading | two_term | edge_corrected | exact (nu may be 0.5) | auto (needs
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
#include "layerjkr/profile.hpp"

namespace layerjkr {

enum class MediumType { winkler, pasternak, filonenko_borodich, layer, half_space };

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
  std::string model;                  ///< resolved model name
  std::string solver = "closed_form"; ///< closed_form | ode
  double w = 0.0;                     ///< [J/m^2]
  double tolerance = 0.0;             ///< relative error target of model "auto", in (0, 1)
};

/// The scene turned into a contact model, with the constants it used.
struct BuiltScene {
  ContactModelPtr model;
  bool has_foundation_constants = false;
  double K = 0.0;  ///< foundation modulus [N/m^3] (layers: mapped)
  double G = 0.0;  ///< shear modulus or tension [N/m] (layers: mapped)
  bool has_effective_modulus = false;
  double E_star = 0.0;  ///< [Pa], layers and half-space
  std::vector<std::string> warnings;
  /// Model "auto": what was chosen, its estimated error, and at which radius [m].
  bool automatic = false;
  std::string chosen_model;
  double estimated_error = 0.0;
  double reference_radius = 0.0;
};

/// Parses a scene from JSON text; `source` names it in error messages.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");

/// Reads and parses a scene file. Throws InputError if it cannot be read.
Scene load_scene(const std::string& path);

/// Builds the contact model of a parsed scene. Model "auto" chooses for contact radii
/// >= a_min [m] (required > 0 for "auto", ignored otherwise).
BuiltScene build_scene(const Scene& scene, double a_min = 0.0);

/// The radius model "auto" should be chosen at for a summary: half the Winkler pull-off
/// radius (which covers the fixed-grips point), or h when there is no adhesion; 0 for
/// scenes whose model is not "auto" (build_scene ignores it then).
double summary_reference_radius(const Scene& scene);

}  // namespace layerjkr
