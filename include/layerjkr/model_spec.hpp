// layerjkr: a typed description of a contact model - which model, with which constants -
// and the one factory that builds it. Scenes (scene.hpp), the automatic choice
// (model_choice.hpp) and the fit (fit.hpp) all build their models through
// make_contact_model, so a model is constructed, and validated, in one place.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "layerjkr/exact_layer.hpp"
#include "layerjkr/layered_medium.hpp"
#include "layerjkr/model.hpp"

namespace layerjkr {

/// A model with its constants; the fields a kind does not use are ignored.
struct ModelSpec {
  ModelKind kind = ModelKind::winkler;
  double K = 0.0;        ///< foundation modulus [N/m^3] (winkler, two_term, full_foundation)
  double G = 0.0;        ///< shear modulus or tension [N/m] (two_term: any sign; full: > 0)
  ElasticLayer layer;    ///< exact, edge_corrected, incompressible, uniform: the layer; half_space: E and nu
  /// exact only: a stack of layers, solved in place of `layer` (which then holds its top
  /// layer, E1 and h1, as the reports and the fit read them). Other kinds refuse a stack.
  std::optional<LayeredMedium> stack;
  bool ode = false;      ///< foundations: P_H by the ODE route (make_ode_foundation)
  ExactLayerOptions exact;  ///< exact: discretisation and range
};

/// Throws DomainError for the first invalid constant of `spec`, with the same checks and
/// messages as the factory, without building anything (no kernel table, no beta fit).
void validate(const ModelSpec& spec);

/// Builds the model `spec` describes for `profile`.
ContactModelPtr make_contact_model(ProfilePtr profile, const ModelSpec& spec);

}  // namespace layerjkr
