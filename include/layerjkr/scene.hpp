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
//                 | layers {layers: [{E, nu, h}, ...] (top first), base: bonded|frictionless|{E, nu}}
//                   (a stack of bonded layers on a rigid base or an elastic half-space)
// model:          layer: leading | two_term | edge_corrected | exact (nu may be 0.5) | incompressible
//                 (nu = 0.5, bonded) | uniform (bonded, nu up to 0.5) | auto (needs
//                 "tolerance": the cheapest model whose measured error is within it);  pasternak, filonenko_borodich: asymptotic |
//                 full;  winkler: winkler (default);  half_space: half_space (default);
//                 layers: exact | leading | two_term (thin-stack laws on a rigid base; two_term
//                 bonded only; judged against exact) | incompressible (every nu = 0.5, bonded: the
//                 squeeze film) | auto (needs "tolerance")
// solver:         closed_form (default) | ode  (foundation models only)
// w:              work of adhesion [J/m^2], >= 0 (absent = 0)
// adhesion:       {"model": jkr (default) | dmt | maugis_dugdale, "sigma0": Dugdale stress [Pa] > 0
//                 | "z0": Lennard-Jones spacing [m] > 0} (adhesion.hpp). maugis_dugdale needs sigma0
//                 or z0; dmt without them is the classical P_H - 2 pi w R (a tip with a radius).
//                 JKR answers are checked against Maugis-Dugdale with sigma0, z0 or z0 = 0.3 nm.
// All values SI. Unknown keys, wrong types and invalid values throw InputError
// naming the key and the value; nothing is ignored.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/adhesion.hpp"
#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model_spec.hpp"
#include "layerjkr/profile.hpp"
#include "layerjkr/types.hpp"
#include "layerjkr/viscoelastic.hpp"

namespace layerjkr {

/// The medium as given in the scene (unused fields are NaN).
struct MediumSpec {
  MediumType type = MediumType::winkler;
  double K = 0.0, G = 0.0, T = 0.0;  ///< foundations [N/m^3], [N/m], [N/m]
  double E = 0.0, nu = 0.0, h = 0.0;  ///< layer / half-space [Pa], [-], [m]; layers: the top layer's
  Base base = Base::bonded;
  LayeredMedium stack;  ///< layers: the stack (top first)
  /// How E relaxes in time (half_space, layer, layers; elastic by default): E is then the
  /// instantaneous modulus (a power law's modulus at t0), nu constant, and a stack's layers all
  /// relax by the same normalised law (viscoelastic.hpp).
  RelaxationLaw relaxation;
};

/// Where a scene came from, for provenance (provenance.hpp): set by parse_scene and load_scene,
/// empty for a scene built in code. Code that changes a parsed scene's fields makes it stale;
/// provenance compares the fields with the JSON and records a stale scene as not reproducible.
struct SceneOrigin {
  std::string json;         ///< the JSON parse_scene read, compact (nlohmann's dump: doubles exact)
  std::string file;         ///< load_scene: the path, as given
  std::string file_sha256;  ///< load_scene: SHA-256 of the bytes parsed (64 lowercase hex digits)
  std::string description;  ///< the parsed fields, described when parsed (what "stale" is judged by)
};

struct Scene {
  ProfilePtr profile;
  MediumSpec medium;
  SceneModel model = SceneModel::winkler;  ///< the scene's model, or the medium's default
  Solver solver = Solver::closed_form;
  double w = 0.0;                     ///< [J/m^2]
  AdhesionSpec adhesion;              ///< how adhesion acts (default JKR) and its Dugdale stress
  double tolerance = 0.0;             ///< relative error target of model "auto", in (0, 1)
  SceneOrigin origin;                 ///< the JSON and file it was read from (empty: built in code)
};

/// Parses a scene from JSON text; `source` names it in error messages.
Scene parse_scene(const std::string& json_text, const std::string& source = "scene");

/// Reads and parses a scene file. Throws InputError if it cannot be read.
Scene load_scene(const std::string& path);

/// What a scene's model resolves to: the one place that reads a scene's medium and model
/// (the answers, model "auto", the fit and the reports all start from here). Cheap: nothing
/// is built. Throws DomainError for invalid constants.
struct ResolvedModel {
  /// The model to build. Model "auto": the exact layer, the fallback its candidates fall back
  /// to and are judged by (model_choice.hpp); the choice needs the radii of an answer.
  ModelSpec spec;
  bool automatic = false;
  double tolerance = 0.0;  ///< model "auto": the relative error target, in (0, 1)
  /// The model `spec` approximates, which its answers are judged against (model_error.hpp):
  /// the exact layer for every thin-layer law, the full foundation for an asymptotic one with
  /// G > 0; none where `spec` solves its medium exactly.
  std::optional<ModelSpec> reference;
  /// True where K and G come from a layer's E, nu and h (leading and two_term on a layer): a
  /// fit of E scales both.
  bool constants_from_layer = false;
  /// The medium's foundation constants as summaries report them: a foundation's own, or a
  /// layer's thin-layer constants (also for "leading", "edge_corrected" and "auto" with
  /// nu < 1/2; none for "exact", "incompressible", "uniform" and the half-space).
  std::optional<double> K;  ///< [N/m^3]
  std::optional<double> G;  ///< [N/m] shear modulus, or the tension T (see g_is_tension)
  bool g_is_tension = false;  ///< Filonenko-Borodich: G holds the membrane tension T
  std::optional<double> E_star;  ///< plane-strain modulus [Pa]: layers and the half-space
  /// The thin-layer constants' validity warnings: something to act on.
  std::vector<std::string> warnings;
  /// What an answer records but does not warn about: the note of an indenter the profile only
  /// approximates by a documented rule (Profile::approximation: a pyramid as its equivalent cone).
  std::vector<std::string> notices;
};
ResolvedModel resolve_model(const Scene& scene);

}  // namespace layerjkr
