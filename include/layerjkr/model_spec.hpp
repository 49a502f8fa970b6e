// layerjkr: a typed description of a contact model - which model, with which constants -
// and the one factory that builds it. Scenes (scene.hpp), the automatic choice
// (model_choice.hpp) and the fit (fit.hpp) all build their models through
// make_contact_model, so a model is constructed, and validated, in one place.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {

/// Every model the library builds.
enum class ModelKind {
  winkler,          ///< p = K w (eq. 41)
  two_term,         ///< p = K w - G lap w inside the contact (eqs. 43-45, corrected force)
  full_foundation,  ///< Pasternak / Filonenko-Borodich on the whole plane (G > 0)
  half_space,       ///< elastic half-space (Galin / Sneddon)
  edge_corrected,   ///< Winkler at a + beta h (exact_layer.hpp)
  exact,            ///< the exact elastic layer (exact_layer.hpp)
  incompressible,   ///< thin incompressible bonded layer, lubrication law (model.hpp)
  uniform,          ///< bonded thin layer, two-term compliance form uniform in nu (model.hpp)
};

/// The name reports print for a kind: "winkler", "two_term", "full_foundation",
/// "half_space", "edge_corrected", "exact", "incompressible", "uniform" (ContactModel::name() of what it builds;
/// the ODE route prints "ode(<kind>)"). Inline: models name themselves on every query.
constexpr const char* model_name(ModelKind kind) {
  switch (kind) {
    case ModelKind::winkler: return "winkler";
    case ModelKind::two_term: return "two_term";
    case ModelKind::full_foundation: return "full_foundation";
    case ModelKind::half_space: return "half_space";
    case ModelKind::edge_corrected: return "edge_corrected";
    case ModelKind::exact: return "exact";
    case ModelKind::incompressible: return "incompressible";
    case ModelKind::uniform: return "uniform";
  }
  return "unknown";
}

/// The kind a model_name() names; nullopt for any other string.
std::optional<ModelKind> model_kind(const std::string& name);

/// A model with its constants; the fields a kind does not use are ignored.
struct ModelSpec {
  ModelKind kind = ModelKind::winkler;
  double K = 0.0;        ///< foundation modulus [N/m^3] (winkler, two_term, full_foundation)
  double G = 0.0;        ///< shear modulus or tension [N/m] (two_term: any sign; full: > 0)
  ElasticLayer layer;    ///< exact, edge_corrected, incompressible, uniform: the layer; half_space: E and nu
  bool ode = false;      ///< foundations: P_H by the ODE route (make_ode_foundation)
  ExactLayerOptions exact;  ///< exact: discretisation and range
};

/// Throws DomainError for the first invalid constant of `spec`, with the same checks and
/// messages as the factory, without building anything (no kernel table, no beta fit).
void validate(const ModelSpec& spec);

/// Builds the model `spec` describes for `profile`.
ContactModelPtr make_contact_model(ProfilePtr profile, const ModelSpec& spec);

}  // namespace layerjkr
