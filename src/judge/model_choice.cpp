// Model choice by a posteriori error against the exact layer (model_choice.hpp).
#include "layerjkr/model_choice.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <functional>

#include "layerjkr/contact.hpp"
#include "layerjkr/error.hpp"
#include "judge/reference_profile.hpp"
#include "layerjkr/model_error.hpp"

namespace layerjkr {
namespace {

void require_tolerance(const char* fn, double tolerance) {
  if (!(tolerance > 0.0 && tolerance < 1.0)) throw DomainError(fn, "tolerance", tolerance, "(0, 1)");
}

// The first candidate whose error (from `judge`) is within tolerance, else the exact layer.
ModelChoice first_within(const ProfilePtr& profile, const std::vector<ModelKind>& kinds,
                         const std::function<ModelSpec(ModelKind)>& spec_of, double tolerance,
                         const ContactModelPtr& exact,
                         const std::function<double(const ContactModelPtr&)>& judge) {
  ModelChoice choice;
  for (ModelKind kind : kinds) {
    ContactModelPtr candidate;
    try {
      candidate = make_contact_model(profile, spec_of(kind));
    } catch (const DomainError&) {
      continue;  // e.g. edge_corrected where a + beta h < 0 for the radii asked
    }
    double error = 0.0;
    try {
      error = judge(candidate);
    } catch (const DomainError&) {
      continue;  // the candidate cannot reach a radius asked for
    }
    if (error <= tolerance) {
      choice.model = kind;
      choice.estimated_error = error;
      choice.contact_model = std::move(candidate);
      choice.reference = exact;
      return choice;
    }
  }
  choice.model = ModelKind::exact;
  choice.contact_model = exact;
  choice.estimated_error = judge(exact);
  return choice;
}

// The judges: the worst estimate over `radii`, or over a summary's pull-off and zero-load point.
std::function<double(const ContactModelPtr&)> along_radii(const ContactModelPtr& exact, double w,
                                                          const std::vector<double>& radii) {
  return [exact, w, &radii](const ContactModelPtr& m) {
    const ModelErrorEstimator estimator(m, m == exact ? nullptr : exact, w);
    const std::vector<double> e = estimator.along(radii);
    return *std::max_element(e.begin(), e.end());
  };
}

std::function<double(const ContactModelPtr&)> at_summary(const ContactModelPtr& exact, const ModelErrorEstimator& judge,
                                                         double w) {
  return [exact, &judge, w](const ContactModelPtr& m) {
    const ModelErrorEstimator estimator = m == exact ? ModelErrorEstimator(exact, nullptr, w) : judge.for_model(m);
    return estimator.summary(summarize(JkrSolution(m, w))).worst();
  };
}

}  // namespace

namespace {
std::function<ModelSpec(ModelKind)> layer_spec(const ElasticLayer& layer) {
  return [layer](ModelKind kind) { return layer_model_spec(kind, layer); };
}
std::function<ModelSpec(ModelKind)> stack_spec(const LayeredMedium& medium) {
  return [medium](ModelKind kind) { return stack_model_spec(kind, medium); };
}
}  // namespace

std::vector<ModelKind> layer_model_candidates(const ElasticLayer& layer) {
  (void)effective_modulus(layer.E, layer.nu);  // validates E and nu
  detail::require_positive("layer_model_candidates", "h", layer.h);
  std::vector<ModelKind> out;
  const bool bonded = layer.base == Base::bonded;
  if (layer.nu < 0.5) {
    const ThinLayerConstants c = thin_layer_constants(layer);
    out.push_back(ModelKind::winkler);
    if (c.G != 0.0) out.push_back(ModelKind::two_term);
    out.push_back(ModelKind::edge_corrected);
    if (c.G > 0.0) out.push_back(ModelKind::full_foundation);
  } else if (bonded) {
    out.push_back(ModelKind::incompressible);
  }
  if (bonded) out.push_back(ModelKind::uniform);
  return out;
}

ModelSpec layer_model_spec(ModelKind kind, const ElasticLayer& layer) {
  ModelSpec spec;
  spec.kind = kind;
  spec.layer = layer;
  if (kind == ModelKind::winkler || kind == ModelKind::two_term || kind == ModelKind::full_foundation) {
    const ThinLayerConstants c = thin_layer_constants(layer);
    spec.K = c.K;
    spec.G = kind == ModelKind::winkler ? 0.0 : c.G;
  }
  return spec;
}

ModelChoice choose_layer_model(const ProfilePtr& profile, const ElasticLayer& layer, double w, double tolerance,
                               const std::vector<double>& radii) {
  const char* fn = "choose_layer_model";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  if (radii.empty()) throw DomainError(fn, "radii (empty)", 0.0, "at least one contact radius");
  for (double a : radii) detail::require_positive(fn, "contact radius", a);
  const ContactModelPtr exact = layer_reference(profile, layer);
  return first_within(profile, layer_model_candidates(layer), layer_spec(layer), tolerance, exact,
                      along_radii(exact, w, radii));
}

ModelChoice choose_layer_model_for_summary(const ProfilePtr& profile, const ElasticLayer& layer, double w,
                                           double tolerance) {
  const char* fn = "choose_layer_model_for_summary";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  const ContactModelPtr exact = layer_reference(profile, layer);
  const ModelErrorEstimator judge(exact, exact, w);  // one search for the exact critical points
  return first_within(profile, layer_model_candidates(layer), layer_spec(layer), tolerance, exact,
                      at_summary(exact, judge, w));
}

std::vector<ModelKind> stack_model_candidates(const LayeredMedium& medium) {
  medium.validate("stack_model_candidates");
  if (medium.substrate) return {};  // no local law on a half-space (theory.md s.4a)
  const ThinStackConstants c = thin_stack_constants(medium);
  std::vector<ModelKind> out;
  if (c.eps == 0.0 && medium.base == Base::bonded) return {ModelKind::incompressible};  // all nu = 1/2
  if (std::isfinite(c.K)) out.push_back(ModelKind::winkler);
  if (medium.base == Base::bonded && c.eps > 0.0 && c.G != 0.0) out.push_back(ModelKind::two_term);
  return out;
}

ModelSpec stack_model_spec(ModelKind kind, const LayeredMedium& medium) {
  ModelSpec spec;
  spec.kind = kind;
  spec.layer = medium.top();
  if (kind == ModelKind::exact) {
    spec.stack = medium;
  } else if (kind == ModelKind::incompressible) {
    spec.layer = equivalent_incompressible_layer(medium);
  } else if (kind == ModelKind::winkler || kind == ModelKind::two_term) {
    const ThinStackConstants c = thin_stack_constants(medium);
    spec.K = c.K;
    spec.G = kind == ModelKind::winkler ? 0.0 : c.G;
  } else {
    throw DomainError("stack_model_spec", std::string("model ") + to_string(kind), 0.0,
                      "exact, winkler, two_term or incompressible for a stack");
  }
  return spec;
}

ModelChoice choose_stack_model(const ProfilePtr& profile, const LayeredMedium& medium, double w, double tolerance,
                               const std::vector<double>& radii) {
  const char* fn = "choose_stack_model";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  if (radii.empty()) throw DomainError(fn, "radii (empty)", 0.0, "at least one contact radius");
  for (double a : radii) detail::require_positive(fn, "contact radius", a);
  const ContactModelPtr exact =
      make_contact_model(detail::reference_profile(profile), stack_model_spec(ModelKind::exact, medium));
  return first_within(profile, stack_model_candidates(medium), stack_spec(medium), tolerance, exact,
                      along_radii(exact, w, radii));
}

ModelChoice choose_stack_model_for_summary(const ProfilePtr& profile, const LayeredMedium& medium, double w,
                                           double tolerance) {
  const char* fn = "choose_stack_model_for_summary";
  require_tolerance(fn, tolerance);
  detail::require_non_negative(fn, "w", w);
  const ContactModelPtr exact =
      make_contact_model(detail::reference_profile(profile), stack_model_spec(ModelKind::exact, medium));
  const ModelErrorEstimator judge(exact, exact, w);
  return first_within(profile, stack_model_candidates(medium), stack_spec(medium), tolerance, exact,
                      at_summary(exact, judge, w));
}

}  // namespace layerjkr
