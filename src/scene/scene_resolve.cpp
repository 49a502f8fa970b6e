// resolve_model (scene.hpp): the one reading of a scene's medium and model.
#include "layerjkr/scene.hpp"

#include <cmath>

#include "layerjkr/error.hpp"
#include "layerjkr/exact_layer.hpp"

namespace layerjkr {
namespace {

ModelSpec exact_layer_spec(const ElasticLayer& layer) {
  ModelSpec spec;
  spec.kind = ModelKind::exact;
  spec.layer = layer;
  return spec;
}

// A foundation medium: its own constants; the asymptotic model with G > 0 approximates the
// full one.
void resolve_foundation(const Scene& s, ResolvedModel& r) {
  const MediumSpec& m = s.medium;
  ModelSpec& spec = r.spec;
  spec.K = m.K;
  if (m.type == MediumType::winkler) {
    spec.kind = ModelKind::winkler;
    r.G = 0.0;  // reported: a Winkler foundation is the two-term one with G = 0
  } else {
    spec.kind = s.model == SceneModel::full ? ModelKind::full_foundation : ModelKind::two_term;
    spec.G = m.type == MediumType::pasternak ? m.G : m.T;
    r.G = spec.G;
    r.g_is_tension = m.type == MediumType::filonenko_borodich;
    if (spec.kind == ModelKind::two_term && spec.G > 0.0) {
      ModelSpec full = spec;
      full.kind = ModelKind::full_foundation;
      r.reference = full;
    }
  }
  r.K = spec.K;
}

// A layer: the exact model needs no thin-layer constants (so nu may be 1/2), nor do the
// incompressible and uniform laws; the others are thin-layer foundations of the layer.
void resolve_layer(const Scene& s, ResolvedModel& r) {
  const MediumSpec& m = s.medium;
  const ElasticLayer layer{m.E, m.nu, m.h, m.base};
  ModelSpec& spec = r.spec;
  spec.layer = layer;
  r.E_star = effective_modulus(m.E, m.nu);
  const auto report_constants = [&](const ThinLayerConstants& c) {
    r.K = c.K;
    r.G = c.G;
  };
  switch (s.model) {
    case SceneModel::automatic:
      spec.kind = ModelKind::exact;
      r.automatic = true;
      r.tolerance = s.tolerance;
      r.reference = exact_layer_spec(layer);
      if (m.nu < 0.5) report_constants(thin_layer_constants(layer));  // where they exist
      return;
    case SceneModel::exact: spec.kind = ModelKind::exact; return;
    case SceneModel::incompressible: spec.kind = ModelKind::incompressible; break;
    case SceneModel::uniform: spec.kind = ModelKind::uniform; break;
    default: {
      const ThinLayerConstants c = thin_layer_constants(layer);
      report_constants(c);
      r.warnings = c.warnings;
      if (s.model == SceneModel::edge_corrected) {
        spec.kind = ModelKind::edge_corrected;
      } else {  // leading, two_term: a foundation whose constants E scales
        const bool leading = s.model == SceneModel::leading || c.G == 0.0;
        spec.kind = leading ? ModelKind::winkler : ModelKind::two_term;
        spec.K = c.K;
        spec.G = s.model == SceneModel::leading ? 0.0 : c.G;
        r.constants_from_layer = true;
      }
    }
  }
  r.reference = exact_layer_spec(layer);
}

// A stack: the exact solver, or a thin-stack law on a rigid base judged against it.
void resolve_stack(const Scene& s, ResolvedModel& r) {
  const LayeredMedium& stack = s.medium.stack;
  ModelSpec exact;
  exact.kind = ModelKind::exact;
  exact.stack = stack;
  exact.layer = stack.top();
  r.E_star = effective_modulus(s.medium.E, s.medium.nu);
  if (s.model == SceneModel::exact) {
    r.spec = exact;
    return;
  }
  if (s.model == SceneModel::automatic) {  // chosen among stack_model_candidates, judged by exact
    r.spec = exact;
    r.automatic = true;
    r.tolerance = s.tolerance;
    r.reference = exact;
    if (!stack.substrate) {
      const ThinStackConstants c = thin_stack_constants(stack);
      if (std::isfinite(c.K)) r.K = c.K;
      if (stack.base == Base::bonded && std::isfinite(c.G)) r.G = c.G;
    }
    return;
  }
  if (s.model == SceneModel::incompressible) {  // the squeeze film of an incompressible stack
    r.spec.kind = ModelKind::incompressible;
    r.spec.layer = equivalent_incompressible_layer(stack);
    r.reference = exact;
    return;
  }
  const char* fn = "thin-stack law";
  const ThinStackConstants c = thin_stack_constants(stack);  // throws on a half-space
  const bool bonded = stack.base == Base::bonded;
  if (!std::isfinite(c.K))
    throw DomainError(fn, "eps = sum h_i (1+nu_i)(1-2nu_i)/(E_i (1-nu_i))", c.eps,
                      "> 0; every layer is incompressible, so the stack has no Winkler spring: its thin law is "
                      "the squeeze film, model 'incompressible'");
  if (s.model == SceneModel::two_term && !bonded)
    throw DomainError(fn, "base", 1.0,
                      "bonded for model 'two_term' (a frictionless stack's k^2 term is not derived): use 'leading' "
                      "or 'exact'");
  r.spec.kind = s.model == SceneModel::leading ? ModelKind::winkler : ModelKind::two_term;
  r.spec.K = c.K;
  r.spec.G = s.model == SceneModel::leading ? 0.0 : c.G;
  r.K = r.spec.K;
  r.G = r.spec.G;
  r.reference = exact;
}

ResolvedModel resolve_medium(const Scene& s) {
  ResolvedModel r;
  r.spec.ode = s.solver == Solver::ode;
  switch (s.medium.type) {
    case MediumType::half_space:
      r.spec.kind = ModelKind::half_space;
      r.spec.layer = {s.medium.E, s.medium.nu, 0.0, Base::bonded};
      r.E_star = effective_modulus(s.medium.E, s.medium.nu);
      break;
    case MediumType::winkler:
    case MediumType::pasternak:
    case MediumType::filonenko_borodich: resolve_foundation(s, r); break;
    case MediumType::layer: resolve_layer(s, r); break;
    case MediumType::layers: resolve_stack(s, r); break;
  }
  return r;
}

}  // namespace

ResolvedModel resolve_model(const Scene& s) {
  ResolvedModel r = resolve_medium(s);
  // An indenter the profile only approximates (a pyramid) is stated on every answer: a documented
  // approximation, a notice rather than a warning.
  if (s.profile)
    if (std::optional<std::string> note = s.profile->approximation()) r.notices.push_back(*note);
  // A relaxing medium answered as an elastic one would be a silent substitution: said, as the
  // numbers are the instantaneous (or, for a power law, the t0) response only.
  if (s.medium.relaxation.kind != RelaxationLaw::Kind::elastic)
    r.warnings.push_back("the medium relaxes (" + s.medium.relaxation.describe() +
                         "); this answer is its elastic response at E, the instantaneous modulus (a power law's "
                         "modulus at t0): its response in time is simulate's with a speed (Lee-Radok and Ting), "
                         "and a fit of a curve with its times");
  return r;
}

}  // namespace layerjkr
