// The one place a ContactModel is built from its description (model_spec.hpp).
#include "layerjkr/model_spec.hpp"

#include <string>

#include "layerjkr/error.hpp"

namespace layerjkr {

void validate(const ModelSpec& spec) {
  const char* fn = "validate(ModelSpec)";
  if (spec.stack) {
    if (spec.kind != ModelKind::exact)
      throw DomainError(fn, "stack", static_cast<double>(spec.stack->layers.size()),
                        std::string("only with model 'exact' (a stack has no model '") + to_string(spec.kind) +
                            "'), the layer count given");
    spec.stack->validate(fn);
    spec.exact.validate();
    return;
  }
  switch (spec.kind) {
    case ModelKind::winkler:
    case ModelKind::two_term:
    case ModelKind::full_foundation:
      detail::require_positive(fn, "K", spec.K);
      detail::require_finite(fn, "G", spec.G);
      if (spec.kind == ModelKind::full_foundation && !(spec.G > 0.0))
        throw DomainError(fn, "G (or tension T)", spec.G,
                          "finite and > 0; for G <= 0 use the asymptotic two-term model, which "
                          "has no exterior solution");
      return;
    case ModelKind::half_space:
      (void)effective_modulus(spec.layer.E, spec.layer.nu);
      return;
    case ModelKind::edge_corrected:
      (void)thin_layer_constants(spec.layer);
      return;
    case ModelKind::exact:
      detail::require_positive(fn, "h", spec.layer.h);
      (void)effective_modulus(spec.layer.E, spec.layer.nu);
      spec.exact.validate();
      return;
    case ModelKind::incompressible:
      (void)make_incompressible_layer(make_paraboloid(1.0), spec.layer);  // checks; costs nothing
      return;
    case ModelKind::uniform:
      (void)uniform_layer_constants(spec.layer);
      return;
  }
}

ContactModelPtr make_contact_model(ProfilePtr profile, const ModelSpec& spec) {
  validate(spec);
  const bool full = spec.kind == ModelKind::full_foundation;
  const double G = spec.kind == ModelKind::winkler ? 0.0 : spec.G;
  switch (spec.kind) {
    case ModelKind::winkler:
    case ModelKind::two_term:
    case ModelKind::full_foundation:
      if (spec.ode)
        return make_ode_foundation(std::move(profile), spec.K, G,
                                   full ? FoundationKind::full : FoundationKind::asymptotic);
      if (full) return make_full_foundation(std::move(profile), spec.K, spec.G);
      if (G == 0.0) return make_winkler(std::move(profile), spec.K);
      return make_two_term(std::move(profile), spec.K, G);
    case ModelKind::half_space:
      return make_half_space(std::move(profile), spec.layer.E, spec.layer.nu);
    case ModelKind::edge_corrected:
      return make_edge_corrected(std::move(profile), spec.layer);
    case ModelKind::exact:
      if (spec.stack) return make_exact_layer(std::move(profile), *spec.stack, spec.exact);
      return make_exact_layer(std::move(profile), spec.layer, spec.exact);
    case ModelKind::incompressible:
      return make_incompressible_layer(std::move(profile), spec.layer);
    case ModelKind::uniform:
      return make_uniform_layer(std::move(profile), spec.layer);
  }
  throw Error("make_contact_model: unknown model kind");
}

}  // namespace layerjkr
